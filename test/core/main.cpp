#define BOOST_TEST_MODULE dcshell_core
#include <boost/test/unit_test.hpp>

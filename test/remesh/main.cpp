#define BOOST_TEST_MODULE dcshell_remesh
#include <boost/test/unit_test.hpp>

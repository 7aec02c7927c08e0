#define BOOST_TEST_MODULE dcshell_unfold
#include <boost/test/unit_test.hpp>

#define BOOST_TEST_MODULE dcshell_cut
#include <boost/test/unit_test.hpp>

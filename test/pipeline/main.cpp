#define BOOST_TEST_MODULE dcshell_pipeline
#include <boost/test/unit_test.hpp>

#include <gtest/gtest.h>
#include "contact/formulas.hpp"
TEST(Placeholder, Brenner) { EXPECT_NEAR(imcol::contact::brenner_lambda(0.01), 101.90, 0.005); }

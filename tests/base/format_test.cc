// base::sig: the significant figures of report and log numbers, with the examples of
// docs/architecture.md "Conventions"; base::excerpt: a bad value quoted in at most 80 characters.
#include <gtest/gtest.h>
#include <limits>
#include <string>

#include "base/format.h"

namespace
{
  using kimp::base::sig;

  TEST(ReadableNumbers, FourSignificantFigures)
  {
    EXPECT_EQ(sig(166.827), "166.8");
    EXPECT_EQ(sig(164.443), "164.4");
    EXPECT_EQ(sig(169.246), "169.2");
    EXPECT_EQ(sig(0.156019374683666), "0.1560");
    EXPECT_EQ(sig(57.5), "57.50");
    EXPECT_EQ(sig(-0.0530542), "-0.05305");
    EXPECT_EQ(sig(1020.8), "1021");
    EXPECT_EQ(sig(60000), "60000");
  }

  TEST(ReadableNumbers, RoundingUpAddsNoFigure)
  {
    EXPECT_EQ(sig(9.99996), "10.00");
    EXPECT_EQ(sig(0.99996), "1.000");
    EXPECT_EQ(sig(999.96), "1000");
  }

  TEST(ReadableNumbers, TwoFiguresForUncertainties)
  {
    EXPECT_EQ(sig(1.10604, 2), "1.1");
    EXPECT_EQ(sig(0.0123, 2), "0.012");
  }

  TEST(ReadableNumbers, ScientificOutsideTheFixedRange)
  {
    EXPECT_EQ(sig(2.5e9), "2.500e+09");
    EXPECT_EQ(sig(1.2345e-5), "1.234e-05");
    EXPECT_EQ(sig(0.0), "0");
    EXPECT_EQ(sig(std::numeric_limits<double>::quiet_NaN()), "nan");
    EXPECT_EQ(sig(-std::numeric_limits<double>::infinity()), "-inf");
  }

  TEST(QuotedValues, AtMostEightyCharacters)
  {
    using kimp::base::excerpt;
    EXPECT_EQ(excerpt("2500 kN/mm"), "2500 kN/mm");
    const std::string eighty(80, 'a');
    EXPECT_EQ(excerpt(eighty), eighty);
    const std::string huge(1 << 20, 'x');
    const std::string quoted = excerpt(huge);
    EXPECT_EQ(quoted.size(), 80u);
    EXPECT_EQ(quoted, std::string(61, 'x') + "... (1048576 bytes)");
    // Never cut inside a UTF-8 character: 60 ASCII bytes, then two-byte characters.
    std::string accents(60, 'a');
    for (int i = 0; i < 100; ++i)
      accents += "\xc3\xa9";
    const std::string cut = excerpt(accents);
    EXPECT_LE(cut.size(), 80u);
    EXPECT_EQ(cut, std::string(60, 'a') + "\xc3\xa9\xc3\xa9... (260 bytes)");
    // A library message: only its long words are shortened.
    EXPECT_EQ(kimp::base::shorten_long_words("--max-steps: " + huge + " is not a number"),
              "--max-steps: " + quoted + " is not a number");
  }
} // namespace

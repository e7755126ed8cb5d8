// Unit tests for gdsmc::analysis::sweep_table: the numbers of swept values and the CSV of --table.
#include "analysis/sweep_table.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace gdsmc::io;
using namespace gdsmc::analysis;

TEST(SweepTable, NumericValues) {
  EXPECT_DOUBLE_EQ(sweep_table::numeric_value("0.7"), 0.7);
  EXPECT_DOUBLE_EQ(sweep_table::numeric_value("1.5d-3"), 1.5e-3);  // Fortran exponent
  EXPECT_DOUBLE_EQ(sweep_table::numeric_value("12"), 12.0);
  EXPECT_DOUBLE_EQ(sweep_table::numeric_value(".true."), 1.0);
  EXPECT_DOUBLE_EQ(sweep_table::numeric_value(".F."), 0.0);
  EXPECT_DOUBLE_EQ(sweep_table::numeric_value("'0.25'"), 0.25);  // a quoted number
  EXPECT_TRUE(std::isnan(sweep_table::numeric_value("'pairs'")));
  EXPECT_TRUE(std::isnan(sweep_table::numeric_value("'0.01, 0.02'")));  // an array
}

TEST(SweepTable, CsvHeaderRowsQuotingAndTexts) {
  sweep_table::Table t;
  t.variables = {"system:restitution(1,2)", "system:number_density"};
  t.points = 2;
  t.values = {0.6, std::nan(""), 0.9, std::nan("")};
  t.texts = {"0.6", "'0.01, 0.02'", "0.9", "'0.02, 0.04'"};
  t.results.push_back({"temperature", "", "", 2, {1.0, 2.0, 3.0, 4.0}, {0.1, 0.2, std::nan(""), 0.4}});
  t.results.push_back({"total_temperature", "", "", 1, {1.5, 3.5}, {0.05, 0.06}});
  EXPECT_EQ(sweep_table::csv(t),
            "\"system:restitution(1,2)\",system:number_density,temperature_1,temperature_1_error,temperature_2,"
            "temperature_2_error,total_temperature,total_temperature_error\n"
            "0.6,\"0.01, 0.02\",1,0.1,2,0.2,1.5,0.05\n"
            "0.9,\"0.02, 0.04\",3,nan,4,0.4,3.5,0.06\n");
}

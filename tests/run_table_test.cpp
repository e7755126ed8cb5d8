// Unit tests for gdsmc::analysis::csv, gdsmc::analysis::json and the column names of gdsmc::analysis::run_table (--table).
#include "analysis/csv.hpp"
#include "analysis/json.hpp"
#include "analysis/run_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace gdsmc::analysis;

TEST(Csv, FieldsNumbersAndTexts) {
  EXPECT_EQ(csv::field("plain"), "plain");
  EXPECT_EQ(csv::field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv::field("say \"x\""), "\"say \"\"x\"\"\"");
  EXPECT_EQ(csv::field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv::number(0.1), "0.1");
  EXPECT_EQ(csv::number(1.0 / 3.0), "0.333333333333");  // 12 significant digits
  EXPECT_EQ(csv::number(-2.5e-300), "-2.5e-300");
  EXPECT_EQ(csv::number(std::nan("")), "nan");
  EXPECT_EQ(csv::number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(csv::number(-std::numeric_limits<double>::infinity()), "-inf");
  const std::vector<csv::Column> columns{{"x,y", {1.0, 2.0}, {}}, {"label", {std::nan(""), 7.0}, {"'a', 'b'", ""}}};
  EXPECT_EQ(csv::write(columns, 2), "\"x,y\",label\n1,\"'a', 'b'\"\n2,7\n");
  EXPECT_EQ(csv::write(columns, 0), "\"x,y\",label\n");
}

TEST(RunTable, ColumnNamesFromTheShapeOfEachObservable) {
  using V = std::vector<std::string>;
  EXPECT_EQ(run_table::column_names("total_temperature", 1), V{"total_temperature"});
  EXPECT_EQ(run_table::column_names("temperature", 1), V{"temperature"});  // one species: no suffix, as sweep tables
  EXPECT_EQ(run_table::column_names("temperature", 3), (V{"temperature_1", "temperature_2", "temperature_3"}));
  EXPECT_EQ(run_table::column_names("number", 2), (V{"number_1", "number_2"}));  // &agg_frag: cluster sizes 1, 2
  // S(S+1)/2 = 6 pairs of three species, row-major upper triangle
  EXPECT_EQ(run_table::column_names("collisions_pair", 6),
            (V{"collisions_pair_1_1", "collisions_pair_1_2", "collisions_pair_1_3", "collisions_pair_2_2",
               "collisions_pair_2_3", "collisions_pair_3_3"}));
  EXPECT_EQ(run_table::column_names("pressure_tensor", 6),
            (V{"pressure_tensor_xx", "pressure_tensor_yy", "pressure_tensor_zz", "pressure_tensor_xy",
               "pressure_tensor_xz", "pressure_tensor_yz"}));
}

TEST(Json, NumbersAndStringsAnyReaderTakes) {
  EXPECT_EQ(json::number(0.1), "0.10000000000000001");
  EXPECT_EQ(json::number(std::nan("")), "null");  // JSON has no NaN ("cooling_rate": [-nan] was not JSON)
  EXPECT_EQ(json::number(-std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(json::array({1.0, std::nan("")}), "[1, null]");
  EXPECT_EQ(json::quote("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(json::quote("0.5,\t2.0\nx\r"), "\"0.5,\\t2.0\\nx\\r\"");  // a TAB from a sweep value
  EXPECT_EQ(json::quote(std::string("\x01\x1f", 2)), "\"\\u0001\\u001f\"");
  EXPECT_EQ(json::quote("restitución"), "\"restitución\"");  // UTF-8 as it is
}

// SPDX-License-Identifier: GPL-2.0-or-later
// Strict number parsing, round-trip formatting and the flushing CSV writer.
#include <catch2/catch.hpp>
#include <cfloat>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "kanegen/runtime/csv.hpp"
#include "kanegen/runtime/text.hpp"

using namespace kanegen::runtime;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("parse_number is strict", "[text]") {
  double v = 0;
  CHECK(parse_number("1", &v));
  CHECK(v == 1.0);
  CHECK(parse_number("-2.5e-3", &v));
  CHECK(v == -2.5e-3);
  CHECK(parse_number("+.5", &v));
  CHECK(v == 0.5);
  v = 7;
  for (const char* bad :
       {"", "1.2x", " 1", "1 ", "nan", "NaN", "inf", "-inf", "0x10", "1e999", "1,2", "--1", "e"}) {
    INFO("'" << bad << "'");
    CHECK_FALSE(parse_number(bad, &v));
  }
  CHECK(v == 7);  // untouched on failure
}

TEST_CASE("parse_number_list and parse_integer", "[text]") {
  std::vector<double> v;
  CHECK(parse_number_list("1,-2,3e1", &v));
  CHECK(v == std::vector<double>{1, -2, 30});
  CHECK(parse_number_list("", &v));
  CHECK(v.empty());
  CHECK_FALSE(parse_number_list("1,,2", &v));
  CHECK_FALSE(parse_number_list("1,", &v));
  CHECK_FALSE(parse_number_list("1;2", &v));
  long n = 0;
  CHECK(parse_integer("-42", &n));
  CHECK(n == -42);
  CHECK_FALSE(parse_integer("4.2", &n));
  CHECK_FALSE(parse_integer("", &n));
  CHECK_FALSE(parse_integer("99999999999999999999999", &n));
}

TEST_CASE("format_double round-trips, JSON numbers and strings", "[text]") {
  for (double x : {0.1, 1.0 / 3.0, -3.141592653589793, 1e-300, 4.9406564584124654e-324, DBL_MAX, -0.0}) {
    const std::string s = format_double(x);
    CHECK(std::strtod(s.c_str(), nullptr) == x);
    double back = 0;
    CHECK(parse_number(s, &back));
    CHECK(back == x);
  }
  CHECK(json_number(std::nan("")) == "null");
  CHECK(json_number(2.5) == "2.5");
  CHECK(json_string("a\"b\\c\n") == "\"a\\\"b\\\\c\\u000a\"");
  const char* const names[] = {"a", "b"};
  CHECK(join_names(names, 2) == "a, b");
}

TEST_CASE("CsvWriter writes each row through to the file", "[csv]") {
  const std::string path = (std::filesystem::temp_directory_path() / "kanegen_runtime_csv_test.csv").string();
  {
    CsvWriter csv(path);
    REQUIRE(csv.ok());
    REQUIRE(csv.write_header({"t", "a,b", "q\"x"}));
    const double row1[] = {0.0, 0.1, 1.0 / 3.0};
    const double row2[] = {1.0, -2e-300, 0.5};
    REQUIRE(csv.write_row(row1, 3));
    // Already on disk while the writer is open: a crash now keeps the row.
    CHECK(slurp(path) == "t,\"a,b\",\"q\"\"x\"\n0,0.10000000000000001,0.33333333333333331\n");
    REQUIRE(csv.write_row(row2, 3));
    CHECK(csv.close());
  }
  CHECK(slurp(path) ==
        "t,\"a,b\",\"q\"\"x\"\n0,0.10000000000000001,0.33333333333333331\n1,-2.0000000000000001e-300,0.5\n");
  std::filesystem::remove(path);
}

TEST_CASE("CsvWriter reports an unwritable path", "[csv]") {
  CsvWriter csv("/nonexistent-dir/x.csv");
  CHECK_FALSE(csv.ok());
  CHECK(csv.error().find("/nonexistent-dir/x.csv") != std::string::npos);
  const double v = 1;
  CHECK_FALSE(csv.write_row(&v, 1));
}

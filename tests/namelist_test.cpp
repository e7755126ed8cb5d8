// Unit tests for gdsmc::io::namelist: the Fortran namelist syntax and its error messages.
#include "io/namelist.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace gdsmc::io::namelist;
using Kind = Value::Kind;

namespace {

const char* const example = R"(! comment line
&system
  n_species      = 2
  mass           = 1.0, 10.0          ! trailing comment
  diameter       = 2*1.0
  restitution(1,2) = 0.5, restitution(2,2)=0.7
  enskog         = .true.
  name = 'it''s', other = "dq ""x"""
  x = 1.5d-3, y = -2E+2, z = .5, w = 3.
  flags = T, F, .t., .False.
/
&output file='run.h5' /
)";

// Parses `text`, expecting an Error, and returns it.
Error error_of(const std::string& text) {
  try {
    parse(text, "test.nml");
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return Error("", 0, "", "", "");
}

// The single value of `name` in the only group of `text`.
Value only_value(const std::string& text, const std::string& name = "x") {
  const Document doc = parse(text, "test.nml");
  const Assignment* a = doc.groups.at(0).find(name);
  if (a == nullptr || a->values.size() != 1) {
    ADD_FAILURE() << "expected one value of " << name << " in:\n" << text;
    return {};
  }
  return a->values[0];
}

}  // namespace

TEST(Namelist, ExampleRoundTrip) {
  const Document doc = parse(example, "example.nml");
  EXPECT_EQ(doc.file, "example.nml");
  EXPECT_EQ(doc.text, example);
  ASSERT_EQ(doc.groups.size(), 2u);

  const Group& sys = doc.groups[0];
  EXPECT_EQ(sys.name, "system");
  EXPECT_EQ(sys.line, 2);
  std::vector<std::string> names;
  for (const Assignment& a : sys.assignments) names.push_back(a.name);
  EXPECT_EQ(names, (std::vector<std::string>{"n_species", "mass", "diameter", "restitution",
                                             "restitution", "enskog", "name", "other", "x", "y",
                                             "z", "w", "flags"}));

  const Assignment& n = sys.assignments[0];
  EXPECT_EQ(n.line, 3);
  EXPECT_TRUE(n.index.empty());
  ASSERT_EQ(n.values.size(), 1u);
  EXPECT_EQ(n.values[0].kind, Kind::Integer);
  EXPECT_EQ(n.values[0].integer, 2);
  EXPECT_EQ(n.values[0].real, 2.0);
  EXPECT_EQ(n.values[0].text, "2");

  const Assignment& mass = sys.assignments[1];
  ASSERT_EQ(mass.values.size(), 2u);
  EXPECT_EQ(mass.values[0].kind, Kind::Real);
  EXPECT_EQ(mass.values[0].real, 1.0);
  EXPECT_EQ(mass.values[1].real, 10.0);
  EXPECT_EQ(mass.values[1].line, 4);

  const Assignment& diameter = sys.assignments[2];
  ASSERT_EQ(diameter.values.size(), 2u);
  for (const Value& v : diameter.values) {
    EXPECT_EQ(v.kind, Kind::Real);
    EXPECT_EQ(v.real, 1.0);
    EXPECT_EQ(v.text, "1.0");
  }

  const Assignment& r12 = sys.assignments[3];
  EXPECT_EQ(r12.index, (std::vector<int>{1, 2}));
  ASSERT_EQ(r12.values.size(), 1u);
  EXPECT_EQ(r12.values[0].real, 0.5);
  const Assignment& r22 = sys.assignments[4];
  EXPECT_EQ(r22.index, (std::vector<int>{2, 2}));
  EXPECT_EQ(r22.line, 6);
  ASSERT_EQ(r22.values.size(), 1u);
  EXPECT_EQ(r22.values[0].real, 0.7);

  const Assignment& enskog = sys.assignments[5];
  ASSERT_EQ(enskog.values.size(), 1u);
  EXPECT_EQ(enskog.values[0].kind, Kind::Logical);
  EXPECT_TRUE(enskog.values[0].logical);

  EXPECT_EQ(sys.assignments[6].values.at(0).kind, Kind::String);
  EXPECT_EQ(sys.assignments[6].values.at(0).string, "it's");
  EXPECT_EQ(sys.assignments[7].values.at(0).string, "dq \"x\"");

  EXPECT_DOUBLE_EQ(sys.assignments[8].values.at(0).real, 1.5e-3);
  EXPECT_EQ(sys.assignments[8].values.at(0).text, "1.5d-3");
  EXPECT_DOUBLE_EQ(sys.assignments[9].values.at(0).real, -200.0);
  EXPECT_EQ(sys.assignments[9].values.at(0).kind, Kind::Real);
  EXPECT_DOUBLE_EQ(sys.assignments[10].values.at(0).real, 0.5);
  EXPECT_DOUBLE_EQ(sys.assignments[11].values.at(0).real, 3.0);
  EXPECT_EQ(sys.assignments[11].values.at(0).kind, Kind::Real);

  const Assignment& flags = sys.assignments[12];
  ASSERT_EQ(flags.values.size(), 4u);
  const bool expected[] = {true, false, true, false};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(flags.values[i].kind, Kind::Logical);
    EXPECT_EQ(flags.values[i].logical, expected[i]);
  }
  EXPECT_EQ(flags.line, 10);

  const Group& out = doc.groups[1];
  EXPECT_EQ(out.name, "output");
  EXPECT_EQ(out.line, 12);
  ASSERT_EQ(out.assignments.size(), 1u);
  EXPECT_EQ(out.assignments[0].values.at(0).string, "run.h5");
  EXPECT_EQ(out.assignments[0].line, 12);
}

TEST(Namelist, FindIsCaseInsensitive) {
  const Document doc = parse("&SyStem MASS = 1, Mass(2) = 3 /", "f");
  ASSERT_NE(doc.find("system"), nullptr);
  EXPECT_EQ(doc.find("SYSTEM"), doc.find("system"));
  EXPECT_EQ(doc.find("output"), nullptr);
  const Group& g = *doc.find("system");
  EXPECT_EQ(g.name, "system");
  const Assignment* a = g.find("mAsS");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->name, "mass");
  EXPECT_TRUE(a->index.empty());  // the first of the two
  EXPECT_EQ(g.assignments[1].name, "mass");
  EXPECT_EQ(g.assignments[1].index, std::vector<int>{2});
  EXPECT_EQ(g.find("diameter"), nullptr);
}

TEST(Namelist, FindReturnsIndexedAssignmentWhenFirst) {
  const Document doc = parse("&g a(3) = 1 /", "f");
  const Assignment* a = doc.groups.at(0).find("a");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->index, std::vector<int>{3});
}

TEST(Namelist, GroupTerminators) {
  const Document doc = parse("&a x = 1 &end\n"
                             "$b y = 2 $end\n"
                             "&c z = 3 &END\n"
                             "$D w = 4 /\n"
                             "&e v = 5 $End\n",
                             "f");
  ASSERT_EQ(doc.groups.size(), 5u);
  const char* names[] = {"a", "b", "c", "d", "e"};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(doc.groups[i].name, names[i]);
    EXPECT_EQ(doc.groups[i].line, static_cast<int>(i) + 1);
    ASSERT_EQ(doc.groups[i].assignments.size(), 1u);
    EXPECT_EQ(doc.groups[i].assignments[0].values.at(0).integer, static_cast<long long>(i) + 1);
  }
}

TEST(Namelist, EmptyGroups) {
  const Document doc = parse("&output /\n&empty\n\n/\n&more&end\n", "f");
  ASSERT_EQ(doc.groups.size(), 3u);
  for (const Group& g : doc.groups) EXPECT_TRUE(g.assignments.empty());
  EXPECT_EQ(doc.groups[1].line, 2);
}

TEST(Namelist, EmptyTextHasNoGroups) {
  EXPECT_TRUE(parse("", "f").groups.empty());
  EXPECT_TRUE(parse("just prose, no groups\n", "f").groups.empty());
}

TEST(Namelist, TextOutsideGroupsIsIgnored) {
  const Document doc = parse("Run notes: R&D budget, 50$ = cheap, a = 1 / x\n"
                             "! commented out: &old x = 1 /\n"
                             "&new x = 1 /  trailing text, even 'quotes and = signs\n"
                             "more notes\n",
                             "f");
  ASSERT_EQ(doc.groups.size(), 1u);
  EXPECT_EQ(doc.groups[0].name, "new");
  EXPECT_EQ(doc.groups[0].line, 3);
}

TEST(Namelist, GroupsMayShareALine) {
  const Document doc = parse("&a x = 1 /&b y = 2 / &c /", "f");
  ASSERT_EQ(doc.groups.size(), 3u);
  EXPECT_EQ(doc.groups[1].name, "b");
  EXPECT_EQ(doc.groups[2].name, "c");
}

TEST(Namelist, CommentsInsideGroups) {
  const Document doc = parse("&g ! comment after the group name, with = and / and 'quote\n"
                             "  ! a whole-line comment &other\n"
                             "  s = 'a ! not a comment' ! a comment\n"
                             "  v = 1, ! comment between values\n"
                             "      2   ! and another\n"
                             "/\n",
                             "f");
  const Group& g = doc.groups.at(0);
  ASSERT_EQ(g.assignments.size(), 2u);
  EXPECT_EQ(g.assignments[0].values.at(0).string, "a ! not a comment");
  EXPECT_EQ(g.assignments[0].line, 3);
  ASSERT_EQ(g.assignments[1].values.size(), 2u);
  EXPECT_EQ(g.assignments[1].values[1].integer, 2);
  EXPECT_EQ(g.assignments[1].values[1].line, 5);
}

TEST(Namelist, ValuesContinueOverLinesAndSeparators) {
  const Document doc = parse("&g\n"
                             "  a = 1 2,3 ,4\n"
                             "      5\n"
                             "\n"
                             "      6, b\n"
                             "  =\n"
                             "  7,\n"
                             "/\n",
                             "f");
  const Group& g = doc.groups.at(0);
  ASSERT_EQ(g.assignments.size(), 2u);
  const Assignment& a = g.assignments[0];
  ASSERT_EQ(a.values.size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(a.values[i].integer, static_cast<long long>(i) + 1);
  EXPECT_EQ(a.values[4].line, 3);
  EXPECT_EQ(a.values[5].line, 5);
  EXPECT_EQ(g.assignments[1].name, "b");
  EXPECT_EQ(g.assignments[1].line, 5);
  EXPECT_EQ(g.assignments[1].values.at(0).line, 7);
}

TEST(Namelist, TrailingCommaBeforeNameOrEnd) {
  const Document doc = parse("&g a = 1,\n b = 2,\n/\n&h c = 'x', &end", "f");
  EXPECT_EQ(doc.groups.at(0).assignments.size(), 2u);
  EXPECT_EQ(doc.groups.at(1).assignments.at(0).values.size(), 1u);
}

TEST(Namelist, NoBlanksNeeded) {
  const Document doc = parse("&g a=1,b(2)=2.5,c='x'/", "f");
  const Group& g = doc.groups.at(0);
  ASSERT_EQ(g.assignments.size(), 3u);
  EXPECT_EQ(g.assignments[1].index, std::vector<int>{2});
  EXPECT_EQ(g.assignments[2].values.at(0).string, "x");
}

TEST(Namelist, Repeat) {
  const Document doc = parse("&g a = 3*1.5, 2, b = 2*'ab', c = 2*T 1*.false., d = 2*-7 /", "f");
  const Group& g = doc.groups.at(0);
  const Assignment& a = *g.find("a");
  ASSERT_EQ(a.values.size(), 4u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(a.values[i].kind, Kind::Real);
    EXPECT_EQ(a.values[i].real, 1.5);
    EXPECT_EQ(a.values[i].text, "1.5");
  }
  EXPECT_EQ(a.values[3].kind, Kind::Integer);
  const Assignment& b = *g.find("b");
  ASSERT_EQ(b.values.size(), 2u);
  EXPECT_EQ(b.values[1].kind, Kind::String);
  EXPECT_EQ(b.values[1].string, "ab");
  const Assignment& c = *g.find("c");
  ASSERT_EQ(c.values.size(), 3u);
  EXPECT_TRUE(c.values[0].logical);
  EXPECT_TRUE(c.values[1].logical);
  EXPECT_FALSE(c.values[2].logical);
  const Assignment& d = *g.find("d");
  ASSERT_EQ(d.values.size(), 2u);
  EXPECT_EQ(d.values[1].integer, -7);
}

TEST(Namelist, Logicals) {
  const std::vector<std::pair<std::string, bool>> cases = {
      {".true.", true}, {".TRUE.", true},   {".True.", true}, {".t.", true},   {".T.", true},
      {"t", true},      {"T", true},        {".false.", false}, {".FALSE.", false},
      {".f.", false},   {".F.", false},     {"f", false},     {"F", false}};
  for (const auto& [text, expected] : cases) {
    const Value v = only_value("&g x = " + text + " /");
    EXPECT_EQ(v.kind, Kind::Logical) << text;
    EXPECT_EQ(v.logical, expected) << text;
    EXPECT_EQ(v.text, text);
  }
}

// `t` and `f` are variable names when followed by '=' or '(' and logicals otherwise.
TEST(Namelist, TAndFAsNames) {
  const Document doc = parse("&g x = t, f\n t = f f(2) = T /", "f");
  const Group& g = doc.groups.at(0);
  ASSERT_EQ(g.assignments.size(), 3u);
  EXPECT_EQ(g.assignments[0].values.size(), 2u);
  EXPECT_EQ(g.assignments[1].name, "t");
  EXPECT_FALSE(g.assignments[1].values.at(0).logical);
  EXPECT_EQ(g.assignments[2].name, "f");
  EXPECT_EQ(g.assignments[2].index, std::vector<int>{2});
  EXPECT_TRUE(g.assignments[2].values.at(0).logical);
}

TEST(Namelist, Strings) {
  EXPECT_EQ(only_value("&g x = 'plain' /").string, "plain");
  EXPECT_EQ(only_value("&g x = \"double\" /").string, "double");
  EXPECT_EQ(only_value("&g x = '' /").string, "");
  EXPECT_EQ(only_value("&g x = '''' /").string, "'");
  EXPECT_EQ(only_value("&g x = 'it''s' /").string, "it's");
  EXPECT_EQ(only_value("&g x = \"say \"\"hi\"\"\" /").string, "say \"hi\"");
  EXPECT_EQ(only_value("&g x = \"it's\" /").string, "it's");
  EXPECT_EQ(only_value("&g x = 'a \"b\"' /").string, "a \"b\"");
  EXPECT_EQ(only_value("&g x = 'a/b, c = &d ! e' /").string, "a/b, c = &d ! e");
  EXPECT_EQ(only_value("&g x = '  padded  ' /").string, "  padded  ");
  const Value v = only_value("&g x = 'it''s' /");
  EXPECT_EQ(v.kind, Kind::String);
  EXPECT_EQ(v.text, "it's");
}

TEST(Namelist, Integers) {
  const std::vector<std::pair<std::string, long long>> cases = {
      {"12", 12}, {"-3", -3}, {"+4", 4}, {"0", 0}, {"007", 7},
      {"9223372036854775807", 9223372036854775807LL}};
  for (const auto& [text, expected] : cases) {
    const Value v = only_value("&g x = " + text + " /");
    EXPECT_EQ(v.kind, Kind::Integer) << text;
    EXPECT_EQ(v.integer, expected) << text;
    EXPECT_EQ(v.real, static_cast<double>(expected)) << text;
    EXPECT_EQ(v.text, text);
  }
}

TEST(Namelist, Reals) {
  const std::vector<std::pair<std::string, double>> cases = {
      {"1.0", 1.0},     {".5", 0.5},       {"3.", 3.0},        {"1e-3", 1e-3},
      {"1.5d-3", 1.5e-3}, {"1.5D+3", 1.5e3}, {"-2E+2", -200.0}, {"+2.5", 2.5},
      {"-.25", -0.25},  {"2d0", 2.0},      {"1.E2", 100.0},    {"6.02214076e23", 6.02214076e23}};
  for (const auto& [text, expected] : cases) {
    const Value v = only_value("&g x = " + text + " /");
    EXPECT_EQ(v.kind, Kind::Real) << text;
    EXPECT_DOUBLE_EQ(v.real, expected) << text;
    EXPECT_EQ(v.text, text);
  }
}

TEST(Namelist, IndexedAssignments) {
  const Document doc = parse("&g a(2) = 1, 2, 3\n"
                             "  b( 1 , 2 ) = 4\n"
                             "  c (3) = 5\n"
                             "  d(1,\n"
                             "    2, 3) = 6\n"
                             "  e(+2) = 7\n"
                             "/",
                             "f");
  const Group& g = doc.groups.at(0);
  ASSERT_EQ(g.assignments.size(), 5u);
  EXPECT_EQ(g.assignments[0].index, std::vector<int>{2});
  EXPECT_EQ(g.assignments[0].values.size(), 3u);
  EXPECT_EQ(g.assignments[1].index, (std::vector<int>{1, 2}));
  EXPECT_EQ(g.assignments[1].line, 2);
  EXPECT_EQ(g.assignments[2].index, std::vector<int>{3});
  EXPECT_EQ(g.assignments[3].index, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(g.assignments[3].line, 4);
  EXPECT_EQ(g.assignments[4].index, std::vector<int>{2});
}

// Only whole-variable repeats are errors: element assignments may override a whole one.
TEST(Namelist, WholeAndIndexedAssignmentOfOneName) {
  const Document doc = parse("&g a = 3*0.0, a(2) = 1.0, a(2) = 2.0 /", "f");
  EXPECT_EQ(doc.groups.at(0).assignments.size(), 3u);
}

TEST(Namelist, SameVariableInDifferentGroups) {
  const Document doc = parse("&a x = 1 /\n&b x = 2 /", "f");
  EXPECT_EQ(doc.groups.size(), 2u);
}

TEST(Namelist, CrLfLineEnds) {
  const Document doc = parse("&g\r\n a = 1\r\n b = 'x'\r\n/\r\n", "f");
  const Group& g = doc.groups.at(0);
  ASSERT_EQ(g.assignments.size(), 2u);
  EXPECT_EQ(g.assignments[1].line, 3);
  EXPECT_EQ(g.assignments[1].values.at(0).string, "x");
}

TEST(Namelist, ParseFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "gdsmc_namelist_test_parse_file.nml";
  {
    std::ofstream out(path, std::ios::binary);
    out << example;
  }
  const Document doc = parse_file(path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(doc.file, path.string());
  EXPECT_EQ(doc.text, example);
  EXPECT_EQ(doc.groups.size(), 2u);
}

TEST(Namelist, EmptyFileNameInMessages) {
  EXPECT_EQ(parse("", "").file, "<input>");
  try {
    parse("&g x = abc /", "");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("<input>:1: &g: x: ", 0), 0u) << e.what();
  }
}

// ---- errors ----

TEST(NamelistError, MessageFormat) {
  const Error e("run.nml", 7, "system", "mass", "bad value 'x'");
  EXPECT_STREQ(e.what(), "run.nml:7: &system: mass: bad value 'x'");
  EXPECT_EQ(e.file, "run.nml");
  EXPECT_EQ(e.line, 7);
  EXPECT_EQ(e.group, "system");
  EXPECT_EQ(e.variable, "mass");
  EXPECT_EQ(e.message, "bad value 'x'");
  EXPECT_STREQ(Error("f", 3, "", "v", "m").what(), "f:3: v: m");
  EXPECT_STREQ(Error("f", 3, "g", "", "m").what(), "f:3: &g: m");
  EXPECT_STREQ(Error("f", 3, "", "", "m").what(), "f:3: m");
  EXPECT_STREQ(Error("f", 0, "", "", "m").what(), "f: m");
  const std::runtime_error& base = e;
  EXPECT_STREQ(base.what(), e.what());
}

TEST(NamelistError, CannotOpenFile) {
  try {
    parse_file("/nonexistent/dir/missing.nml");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.file, "/nonexistent/dir/missing.nml");
    EXPECT_NE(std::string(e.what()).find("missing.nml: cannot open"), std::string::npos)
        << e.what();
  }
}

TEST(NamelistError, UnterminatedString) {
  const Error e = error_of("&system\n"
                           "  a = 1\n"
                           "  name = 'abc\n"
                           "  b = 2 /\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.group, "system");
  EXPECT_EQ(e.variable, "name");
  EXPECT_NE(std::string(e.what()).find("test.nml:3: &system: name: unterminated string"),
            std::string::npos)
      << e.what();
  // At the end of the file, too.
  EXPECT_EQ(error_of("&g\n\n x = \"abc").line, 3);
  // A doubled quote does not close the string.
  EXPECT_EQ(error_of("&g\n x = 'it''\n/").line, 2);
}

TEST(NamelistError, UnterminatedGroup) {
  const Error e = error_of("! header\n"
                           "&output /\n"
                           "\n"
                           "&system\n"
                           "  a = 1\n"
                           "  b = 2\n");
  EXPECT_EQ(e.line, 4);
  EXPECT_EQ(e.group, "system");
  EXPECT_TRUE(e.variable.empty());
  const std::string what = e.what();
  EXPECT_NE(what.find("&system"), std::string::npos) << what;
  EXPECT_NE(what.find("unterminated"), std::string::npos) << what;
  EXPECT_NE(what.find("line 4"), std::string::npos) << what;
  EXPECT_EQ(what.rfind("test.nml:4: &system: ", 0), 0u) << what;
  // The terminator inside a comment or a string does not count.
  EXPECT_EQ(error_of("&g a = 1 ! /\n").line, 1);
  EXPECT_EQ(error_of("\n&g a = '/' ").line, 2);
  EXPECT_NE(std::string(error_of("&empty").what()).find("unterminated"), std::string::npos);
}

TEST(NamelistError, GroupInsideGroup) {
  const Error e = error_of("&system\n"
                           "  a = 1\n"
                           "&output file = 'x' /\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.group, "system");
  const std::string what = e.what();
  EXPECT_NE(what.find("&output starts inside group &system (started at line 1)"),
            std::string::npos)
      << what;
  EXPECT_EQ(error_of("&a\n\n$b /").line, 3);
}

TEST(NamelistError, ValueWithoutName) {
  const Error e = error_of("&g = 1 /");
  EXPECT_EQ(e.line, 1);
  EXPECT_EQ(e.group, "g");
  EXPECT_NE(std::string(e.what()).find("without a variable name"), std::string::npos) << e.what();
  const Error e2 = error_of("&g\n 1, 2 /");
  EXPECT_EQ(e2.line, 2);
  EXPECT_NE(std::string(e2.what()).find("without a variable name"), std::string::npos);
  EXPECT_NE(std::string(e2.what()).find("'1'"), std::string::npos) << e2.what();
  EXPECT_NE(std::string(error_of("&g 'str' /").what()).find("without a variable name"),
            std::string::npos);
  // A word not followed by '=' before any assignment.
  EXPECT_NE(std::string(error_of("&g abc /").what()).find("without a variable name"),
            std::string::npos);
  // '=' after a value.
  const Error e3 = error_of("&g a = 1\n = 2 /");
  EXPECT_EQ(e3.line, 2);
  EXPECT_NE(std::string(e3.what()).find("without a variable name"), std::string::npos);
}

TEST(NamelistError, BadTokens) {
  struct Case {
    std::string value;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"1.2.3", "bad value '1.2.3'"},
      {"abc", "bad value 'abc': an unquoted word"},
      {"true", "bad value 'true'"},
      {".true", "bad value '.true'"},
      {".tru.", "bad value '.tru.'"},
      {"1e", "bad value '1e'"},
      {"1e+", "bad value '1e+'"},
      {"1.0e5.", "bad value '1.0e5.'"},
      {".", "bad value '.'"},
      {"-", "bad value '-'"},
      {"+-1", "bad value '+-1'"},
      {"1_8", "bad value '1_8'"},
      {"0x10", "bad value '0x10'"},
      {"inf", "bad value 'inf'"},
      {"nan", "bad value 'nan'"},
      {"(1.0,2.0)", "bad value '(1.0'"},
      {"1.0+3", "bad value '1.0+3'"},
      {"a%b", "bad value 'a%b'"},
      {"1=2", "bad value '1=2'"},
  };
  for (const Case& c : cases) {
    const Error e = error_of("&g\n\n  x = 1,\n  " + c.value + "\n/");
    EXPECT_EQ(e.line, 4) << c.value;
    EXPECT_EQ(e.variable, "x") << c.value;
    EXPECT_NE(std::string(e.what()).find("test.nml:4: &g: x: " + c.expected), std::string::npos)
        << c.value << " -> " << e.what();
  }
}

TEST(NamelistError, NumbersOutOfRange) {
  EXPECT_NE(std::string(error_of("&g x = 9223372036854775808 /").what()).find("out of range"),
            std::string::npos);
  EXPECT_NE(std::string(error_of("&g x = 1d999 /").what()).find("out of range"),
            std::string::npos);
}

TEST(NamelistError, MissingSeparator) {
  EXPECT_EQ(error_of("&g\n x = 'a'b /").line, 2);
  EXPECT_NE(std::string(error_of("&g x = 'a'\"b\" /").what()).find("separator"),
            std::string::npos);
  EXPECT_NE(std::string(error_of("&g x = ab'c' /").what()).find("quote"), std::string::npos);
}

TEST(NamelistError, BadIndex) {
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"a(0) = 1", "bad index '0' (indices are integers from 1)"},
      {"a(x) = 1", "bad index 'x'"},
      {"a(-1) = 1", "bad index '-1'"},
      {"a(1.5) = 1", "bad index '1.5'"},
      {"a(1, 0) = 1", "bad index '0'"},
      {"a(1:3) = 1", "array sections are not supported"},
      {"a() = 1", "missing index"},
      {"a(1,) = 1", "missing index"},
      {"a(99999999999) = 1", "bad index '99999999999'"},
      {"a(1 2) = 1", "expected ',' or ')'"},
      {"a(1) 5", "expected '=' after 'a(...)'"},
  };
  for (const Case& c : cases) {
    const Error e = error_of("&g\n  b = 1\n  " + c.text + "\n/");
    EXPECT_EQ(e.line, 3) << c.text;
    EXPECT_EQ(e.group, "g") << c.text;
    EXPECT_EQ(e.variable, "a") << c.text;
    EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos)
        << c.text << " -> " << e.what();
  }
}

TEST(NamelistError, BadRepeatCount) {
  const std::vector<std::string> counts = {"0", "-1", "1.5", "x", "+2", ""};
  for (const std::string& count : counts) {
    const Error e = error_of("&g\n x = " + count + "*1.0 /");
    EXPECT_EQ(e.line, 2) << count;
    EXPECT_EQ(e.variable, "x") << count;
    EXPECT_NE(std::string(e.what()).find("repeat count must be a positive integer, found '" +
                                         count + "' in '" + count + "*1.0'"),
              std::string::npos)
        << count << " -> " << e.what();
  }
  EXPECT_NE(std::string(error_of("&g x = 10000000000*1.0 /").what()).find("larger than"),
            std::string::npos);
  // `r*` alone is a Fortran null value, and `r*r*v` is not a value.
  EXPECT_NE(std::string(error_of("&g x = 3* /").what()).find("'3*' without a value"),
            std::string::npos);
  EXPECT_NE(std::string(error_of("&g x = 3*, 1 /").what()).find("without a value"),
            std::string::npos);
  EXPECT_NE(std::string(error_of("&g x = 2*3*1 /").what()).find("bad value '3*1'"),
            std::string::npos);
}

TEST(NamelistError, NullValues) {
  const Error e = error_of("&g\n a = 1,, 2 /");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(std::string(e.what()).find("null values are not supported"), std::string::npos);
  EXPECT_EQ(error_of("&g a = , 2 /").variable, "a");
  EXPECT_EQ(error_of("&g a = 1, ,\n b = 2 /").line, 1);
  EXPECT_EQ(error_of("&g , a = 1 /").line, 1);
  const Error e2 = error_of("&g\n a =\n b = 2 /");
  EXPECT_EQ(e2.line, 3);  // found at the next name
  EXPECT_EQ(e2.variable, "a");
  EXPECT_NE(std::string(e2.what()).find("no value after '='"), std::string::npos);
  EXPECT_EQ(error_of("&g a = /").variable, "a");
  EXPECT_EQ(error_of("&g a = &end").variable, "a");
}

TEST(NamelistError, RepeatedVariable) {
  const Error e = error_of("&system\n"
                           "  mass = 1.0\n"
                           "  diameter = 1.0\n"
                           "  MASS = 2.0\n"
                           "/");
  EXPECT_EQ(e.line, 4);
  EXPECT_EQ(e.group, "system");
  EXPECT_EQ(e.variable, "mass");
  EXPECT_STREQ(e.what(),
               "test.nml:4: &system: mass: assigned twice in one group (first at line 2)");
}

TEST(NamelistError, RepeatedGroup) {
  const Error e = error_of("&output /\n"
                           "&system a = 1 /\n"
                           "\n"
                           "&OUTPUT file = 'x' /\n");
  EXPECT_EQ(e.line, 4);
  EXPECT_EQ(e.group, "output");
  EXPECT_STREQ(e.what(), "test.nml:4: &output: group name repeated (first at line 1)");
}

TEST(NamelistError, EndOutsideGroup) {
  const Error e = error_of("&g a = 1 / b = 2\n&end\n");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(std::string(e.what()).find("'&end' outside a group"), std::string::npos);
}

// Free text outside the groups is a comment (Fortran's rule), but a line that starts with an assignment is a
// variable no group reads (a '/' ended its group early): refused, naming the group before it.
TEST(NamelistError, AssignmentOutsideAnyGroup) {
  Error e = error_of("&dsmc n_particles = 200\n/\n  t_end = 10.0\n&output /\n");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.variable, "t_end");
  EXPECT_STREQ(e.what(), "test.nml:3: t_end: an assignment outside any group is not read (&dsmc of line 1 ended "
                         "before it: a '/' too early?)");
  e = error_of("mass(2) = 1.0\n&system /\n");
  EXPECT_EQ(e.line, 1);
  EXPECT_NE(std::string(e.what()).find("(no group has begun: &name first)"), std::string::npos) << e.what();
}

TEST(NamelistError, StrayAmpersand) {
  const Error e = error_of("&g a = 1\n & /");
  EXPECT_EQ(e.line, 2);
  EXPECT_NE(std::string(e.what()).find("stray '&'"), std::string::npos);
}

TEST(NamelistError, MessagesAreOneLine) {
  const std::vector<std::string> bad = {"&g\n x = 'a\n/", "&g\n x = 1", "&g = 1 /",
                                        "&g x = 1.2.3 /", "&g x = abc /", "&g a(0) = 1 /",
                                        "&g x = 0*1.0 /", "&g a = 1 a = 2 /", "&a /\n&a /",
                                        "&a\n&b /"};
  for (const std::string& text : bad) {
    const std::string what = error_of(text).what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind("test.nml:", 0), 0u) << what;
  }
}

TEST(Namelist, ClosestName) {
  const std::vector<std::string> names = {"temperature", "mass", "diameter", "restitution",
                                          "n_species"};
  EXPECT_EQ(closest_name("tmeperature", names), "temperature");  // one transposition
  EXPECT_EQ(closest_name("temprature", names), "temperature");
  EXPECT_EQ(closest_name("Mass", names), "mass");
  EXPECT_EQ(closest_name("mas", names), "mass");
  EXPECT_EQ(closest_name("diamter", names), "diameter");
  EXPECT_EQ(closest_name("nspecies", names), "n_species");
  EXPECT_EQ(closest_name("restituion", names), "restitution");
  EXPECT_EQ(closest_name("volume", names), "");
  EXPECT_EQ(closest_name("x", names), "");
  EXPECT_EQ(closest_name("mass", {}), "");
  // Within max(2, size/3): "ab" -> "abcd" is 2 edits, "ab" -> "abcde" is 3.
  EXPECT_EQ(closest_name("ab", {"abcde"}), "");
  EXPECT_EQ(closest_name("ab", {"abcd"}), "abcd");
  // Unrestricted Damerau-Levenshtein: "ca" -> "abc" is 2 (optimal string alignment gives 3).
  EXPECT_EQ(closest_name("ca", {"abc"}), "abc");
  // Ties go to the first candidate; candidates are returned as given.
  EXPECT_EQ(closest_name("cat", {"cut", "cot"}), "cut");
  EXPECT_EQ(closest_name("Mass", {"MASS"}), "MASS");
}

// Issue 12, messages: one readable line whatever the bytes of the file.
TEST(NamelistMessages, ByteOrderMarkIsAccepted) {
  const Document doc = parse("\xEF\xBB\xBF&system x = 1 /\n&dsmc y = 2 /\n", "test.nml");
  ASSERT_EQ(doc.groups.size(), 2u);
  EXPECT_EQ(doc.groups[0].name, "system");
  EXPECT_EQ(doc.groups[1].line, 2);
}

TEST(NamelistMessages, NulByteIsRefusedWithItsLine) {
  const Error e = error_of(std::string("! comment\n&system\n  x = 1 ! a\0b\n/\n", 30));
  EXPECT_EQ(e.line, 3);
  EXPECT_NE(std::string(e.what()).find("test.nml:3: contains a NUL byte"), std::string::npos) << e.what();
}

TEST(NamelistMessages, LongNamesAndControlCharactersAreCutAndEscaped) {
  const Error e("f.nml", 3, "system", std::string(100000, 'x'), "value 'a\nb' is bad " + std::string(5000, 'y'));
  const std::string m = e.what();
  EXPECT_LT(m.size(), 1200u);
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  EXPECT_NE(m.find("f.nml:3: &system: " + std::string(64, 'x') + "...: value 'a\\nb' is bad"), std::string::npos);
  EXPECT_EQ(m.substr(m.size() - 3), "...");
}

TEST(NamelistMessages, EmptyFileAndDirectory) {
  const auto dir = std::filesystem::temp_directory_path() / ("gdsmc-nml-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto empty = (dir / "empty.nml").string();
  std::ofstream(empty).close();
  for (const auto& [path, words] : {std::pair{empty, std::string(": is empty")},
                                    std::pair{dir.string(), std::string(": is a directory")}}) {
    try {
      parse_file(path);
      ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).find(path + words), 0u) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

// A name whose '=' was forgotten, at the start of a later line after a value with no comma behind it, is read
// as a value of the assignment before it: the error names it, its line and the '=' it lacks, not the variable
// before it. On the assignment's own line, after a comma, as the first value, second on its line, with a repeat
// count or when it is not a plain name, the word is that variable's bad value (NamelistError.BadTokens: 'x = 1,'
// then 'abc').
TEST(Namelist, AWordWithoutEqualsOnALaterLineIsNamed) {
  const Error later = error_of("&system\n n_species = 2\n mass 1.0, 2.0\n/\n");
  EXPECT_EQ(later.line, 3);
  EXPECT_EQ(later.group, "system");
  EXPECT_EQ(later.variable, "mass");
  EXPECT_NE(later.message.find("'mass' without '=': expected 'mass = value'"), std::string::npos) << later.what();
  EXPECT_NE(later.message.find("a value of n_species from line 2"), std::string::npos) << later.what();
  const Error same = error_of("&system\n n_species = 2 mass 1.0\n/\n");
  EXPECT_EQ(same.line, 2);
  EXPECT_EQ(same.variable, "n_species");
  EXPECT_NE(same.message.find("bad value 'mass': an unquoted word"), std::string::npos) << same.what();
  // (after a comma, as the first value, second on its line, repeated, not a plain name)
  for (const char* text : {"&system\n n_species = 2,\n mass 1.0\n/\n", "&system\n n_species =\n mass 1.0\n/\n",
                           "&system\n n_species = 2\n 3 mass\n/\n", "&system\n n_species = 2\n 3*mass\n/\n",
                           "&system\n n_species = 2\n mass-law 1\n/\n"}) {
    const Error value = error_of(text);
    EXPECT_EQ(value.line, 3) << text;
    EXPECT_EQ(value.variable, "n_species") << text;
    EXPECT_NE(value.message.find("bad value '"), std::string::npos) << value.what();
    EXPECT_EQ(value.message.find("without '='"), std::string::npos) << value.what();
  }
}

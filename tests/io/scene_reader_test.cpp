// The strict TOML reader: every kind of mistake gives a SceneError with the exact line and the
// exact message a user sees.
#include <gtest/gtest.h>

#include <functional>

#include "io/scene_reader.hpp"
#include "io/setting_check.hpp"
#include "io_test_util.hpp"

namespace isomuscle::io {
namespace {

using testing_util::line_containing;

// A parsed document and its root reader (the reader points into the document).
struct Document {
  explicit Document(std::string text_in)
      : text(std::move(text_in)),
        table(parse_toml_text(text, "scene.toml")),
        root(table, "scene.toml") {}
  std::string text;
  toml::table table;
  SceneTable root;
};

// Runs f, which must throw SceneError, and returns the error.
SceneError scene_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError thrown";
  return SceneError("", 0, 0, "");
}

TEST(SceneReader, UnknownKeyNamesLineSuggestionAndValidKeys) {
  Document d(
      "# muscle settings\n"
      "[muscle]\n"
      "material = \"lu2010\"\n"
      "materal = 3\n"
      "fibres = 1\n");
  SceneTable muscle = d.root.table("muscle", required);
  EXPECT_EQ(muscle.string("material", required), "lu2010");
  muscle.allow("parameters");
  EXPECT_EQ(muscle.number("fibres", 0.0), 1.0);
  const SceneError e = scene_error([&] { muscle.finish(); });
  EXPECT_EQ(e.line(), 4);
  EXPECT_STREQ(e.what(),
               "scene.toml:4: unknown key 'materal' in [muscle]; did you mean 'material'? valid "
               "keys: material, parameters, fibres");
}

TEST(SceneReader, UnknownKeysAreReportedInFileOrderWithoutFarFetchedSuggestions) {
  Document d("[time]\nzzz = 1\nend = 2\naaa = 3\n");
  SceneTable time = d.root.table("time", required);
  time.number("end", required);
  const SceneError e = scene_error([&] { time.finish(); });
  EXPECT_EQ(e.line(), 2);  // zzz comes first in the file although aaa sorts first
  EXPECT_EQ(e.message(), "unknown key 'zzz' in [time]; valid keys: end");
}

TEST(SceneReader, UnknownTopLevelTableIsCalledATable) {
  Document d("[geometry]\n\n[materal]\nmodel = \"x\"\n");
  d.root.allow("geometry");
  d.root.allow("material");
  const SceneError e = scene_error([&] { d.root.finish(); });
  EXPECT_STREQ(e.what(),
               "scene.toml:3: unknown table [materal]; did you mean [material]? valid keys: "
               "geometry, material");
}

TEST(SceneReader, WrongTypesSayWhatWasExpectedAndWhatWasFound) {
  Document d("[time]\nend = 1\ndt = \"abc\"\nsteps = 2.5\nadaptive = 1\nname = 3\n");
  SceneTable time = d.root.table("time", required);
  EXPECT_STREQ(scene_error([&] { time.number("dt", 0.1); }).what(),
               "scene.toml:3: 'dt' in [time] must be a number, got a string (\"abc\")");
  EXPECT_STREQ(scene_error([&] { time.integer("steps", 1); }).what(),
               "scene.toml:4: 'steps' in [time] must be an integer, got a floating-point number "
               "(2.5)");
  EXPECT_STREQ(scene_error([&] { time.boolean("adaptive", true); }).what(),
               "scene.toml:5: 'adaptive' in [time] must be a boolean (true or false), got an "
               "integer (1)");
  EXPECT_STREQ(scene_error([&] { time.string("name", ""); }).what(),
               "scene.toml:6: 'name' in [time] must be a string, got an integer (3)");
  EXPECT_STREQ(scene_error([&] { time.optional_table("end"); }).what(),
               "scene.toml:2: 'end' in [time] must be a table, got an integer (1)");
  // Integers are numbers: end = 1 reads as 1.0.
  EXPECT_EQ(time.number("end", required), 1.0);
}

TEST(SceneReader, OutOfRangeAndNonFiniteValues) {
  const std::string text =
      "[time]\n"
      "end = 0.2\n"
      "\n"
      "# the step\n"
      "\n"
      "\n"
      "dt = -0.001\n"
      "dt_min = nan\n"
      "count = 4000000000\n"
      "order = 7\n";
  Document d(text);
  SceneTable time = d.root.table("time", required);
  const SceneError e = scene_error([&] { time.number("dt", required, Range::positive()); });
  EXPECT_EQ(e.line(), 7);
  EXPECT_STREQ(e.what(), "scene.toml:7: 'dt' in [time] must be > 0 (got -0.001)");
  EXPECT_STREQ(scene_error([&] { time.number("dt_min", 1.0); }).what(),
               "scene.toml:8: 'dt_min' in [time] must be a finite number (got nan)");
  EXPECT_STREQ(scene_error([&] { time.integer("count", 1); }).what(),
               "scene.toml:9: 'count' in [time] is too large (got 4000000000)");
  EXPECT_STREQ(scene_error([&] { time.integer("order", 1, Range::closed(1, 4)); }).what(),
               "scene.toml:10: 'order' in [time] must be in [1, 4] (got 7)");
  EXPECT_EQ(time.number("end", required, Range{0.0, 1.0, true, false}), 0.2);
}

TEST(SceneReader, BadChoicesListTheValidOnesAndSuggestNearMisses) {
  Document d(
      "[geometry]\niges = \"a.igs\"\ncentreline = \"x\"\n[solver]\nlinear_solver = \"chomod\"\n");
  SceneTable geometry = d.root.table("geometry", required);
  EXPECT_STREQ(scene_error([&] {
                 geometry.choice("centreline", "v", {"u", "v"});
               }).what(),
               "scene.toml:3: 'centreline' in [geometry] must be one of u, v (got \"x\")");
  SceneTable solver = d.root.table("solver", required);
  EXPECT_STREQ(scene_error([&] {
                 solver.choice("linear_solver", "cholmod", {"cholmod", "umfpack"});
               }).what(),
               "scene.toml:5: 'linear_solver' in [solver] must be one of cholmod, umfpack (got "
               "\"chomod\"); did you mean \"cholmod\"?");
}

TEST(SceneReader, MissingRequiredKeyPointsAtTheTableAndAtANearMiss) {
  const std::string text = "description = \"x\"\n\n[time]\nend = 1\ndtt = 0.1\n";
  Document d(text);
  SceneTable time = d.root.table("time", required);
  const SceneError e = scene_error([&] { time.number("dt", required); });
  EXPECT_EQ(e.line(), line_containing(text, "[time]"));
  EXPECT_STREQ(e.what(),
               "scene.toml:3: missing required key 'dt' in [time]; found 'dtt' on line 5: a "
               "misspelling?");
  Document plain("[time]\nend = 1\n");
  SceneTable time2 = plain.root.table("time", required);
  EXPECT_STREQ(scene_error([&] { time2.number("dt", required); }).what(),
               "scene.toml:1: missing required key 'dt' in [time]");
  // A missing table has no line of its own.
  const SceneError t = scene_error([&] { plain.root.table("material", required); });
  EXPECT_EQ(t.line(), 0);
  EXPECT_STREQ(t.what(), "scene.toml: missing required table [material]");
}

TEST(SceneReader, SyntaxErrorsCarryLineAndColumn) {
  const std::string text = "[time]\nend = 1\n\ndt = 0.1.2\n";
  const SceneError e = scene_error([&] { (void)parse_toml_text(text, "scene.toml"); });
  EXPECT_EQ(e.line(), 4);
  EXPECT_EQ(e.column(), 9);
  EXPECT_EQ(std::string(e.what()).rfind("scene.toml:4:9: TOML syntax error: ", 0), 0u) << e.what();
  const SceneError twice =
      scene_error([&] { (void)parse_toml_text("[time]\nend = 1\nend = 2\n", "scene.toml"); });
  EXPECT_EQ(twice.line(), 3);
  EXPECT_NE(std::string(twice.what()).find("end"), std::string::npos) << twice.what();
}

// A non-ASCII character where toml++ 3.3.0 asks whether it is whitespace, which is undefined
// behaviour there (found by fuzz/scene_parser_fuzzer; fuzz/regressions/scene_parser/), is a syntax
// error at its line and column; non-ASCII text in strings and comments, and TOML that only looks
// like the bad cases (quotes and brackets in strings, nested arrays), still parses.
TEST(SceneReader, NonAsciiOutsideStringsIsASyntaxErrorBeforeTomlPlusPlusSeesIt) {
  const auto error = [](const std::string& text) {
    return scene_error([&] { parse_toml_text(text, "scene.toml"); });
  };
  EXPECT_STREQ(error("[geometry]\niges\xd0\xa7 = \"barrel.igs\"\n").what(),
               "scene.toml:2:5: TOML syntax error: a non-ASCII character outside a string or "
               "comment");
  EXPECT_EQ(error("dt = 5'\xc2\xb5s'\n").column(), 8);           // no string starts after 5
  EXPECT_EQ(error("n = 0='\xc4\x91'\n").column(), 8);            // nor inside the value 0='
  EXPECT_EQ(error("s = \"\"\"\\\xc2\xa7\"\"\"\n").column(), 9);  // not an escape
  EXPECT_EQ(error("s = \"\"\"\\ \xc2\xb5\"\"\"\n").column(), 10);
  const SceneError backslash = error("s = \"\"\"\\\n  \xc2\xa7\"\"\"\n");
  EXPECT_EQ(backslash.line(), 2);
  EXPECT_EQ(backslash.column(), 3);
  EXPECT_NO_THROW(
      parse_toml_text("\xEF\xBB\xBF# r\xc3\xa9sum\xc3\xa9, 5 \xc2\xb5m\n"
                      "description = \"r\xc3\xa9sum\xc3\xa9 \\\" \xd0\xa7\"  # \xc2\xb0\n"
                      "quoted = '\xc2\xb5 \\'\n"
                      "text = \"\"\"\n\xd0\xa7 \\\n  more \xc2\xb5\"\"\"\"\n"
                      "raw = '''\n\xd0\xa7'''\n"
                      "times = [\n  [\"\xc2\xb5\", '\xc2\xb0'],\n  {a.\"\xc3\xa9\" = 1},\n]\n"
                      "[ \"t\xc3\xa9\" . '\xc2\xb5' ]\n"
                      "[[probe]]\n"
                      "name = \"tip\"\n",
                      "scene.toml"));
}

TEST(SceneReader, ArraysCheckLengthAndElementsAtTheElementsLine) {
  const std::string text =
      "[fibres]\n"
      "vector = [0, 0]\n"
      "origin = [\n"
      "  0.0,\n"
      "  \"one\",\n"
      "  2.0,\n"
      "]\n"
      "refine = [1, -2, 0]\n"
      "fields = [\"J\", \"J\"]\n"
      "kinds = [\"J\", \"volum\"]\n"
      "good = [1, 2.5, 3]\n";
  Document d(text);
  SceneTable f = d.root.table("fibres", required);
  EXPECT_STREQ(scene_error([&] { f.optional_vector3("vector"); }).what(),
               "scene.toml:2: 'vector' in [fibres] must hold 3 numbers (got 2)");
  EXPECT_STREQ(scene_error([&] { f.optional_vector3("origin"); }).what(),
               "scene.toml:5: element 2 of 'origin' in [fibres] must be a number, got a string "
               "(\"one\")");
  EXPECT_STREQ(scene_error([&] { f.optional_integers("refine", 3, Range::non_negative()); }).what(),
               "scene.toml:8: element 2 of 'refine' in [fibres] must be >= 0 (got -2)");
  EXPECT_STREQ(scene_error([&] { f.optional_strings("fields"); }).what(),
               "scene.toml:9: element 2 of 'fields' in [fibres] repeats \"J\"");
  EXPECT_STREQ(scene_error([&] {
                 f.optional_strings("kinds", {"J", "volume"});
               }).what(),
               "scene.toml:10: element 2 of 'kinds' in [fibres] must be one of J, volume (got "
               "\"volum\"); did you mean \"volume\"?");
  EXPECT_EQ(f.vector3("good", required), (std::array<double, 3>{1.0, 2.5, 3.0}));
  EXPECT_STREQ(scene_error([&] {
                 f.optional_numbers("missing_not", 0);
                 f.numbers("absent", required);
               }).what(),
               "scene.toml:1: missing required key 'absent' in [fibres]");
}

TEST(SceneReader, ArraysOfTablesAndInlineTablesAreNamedByPosition) {
  const std::string text =
      "[[boundary]]\n"
      "face = \"v0\"\n"
      "\n"
      "[[boundary]]\n"
      "face = { point = [0, 0, 0], nrmal = [0, 0, 1] }\n"
      "type = \"fixed\"\n";
  Document d(text);
  std::vector<SceneTable> entries = d.root.tables("boundary");
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries[0].name(), "[[boundary]] #1");
  EXPECT_EQ(entries[1].name(), "[[boundary]] #2");
  EXPECT_EQ(entries[1].line(), 4);
  SceneTable face = entries[1].table("face", required);
  EXPECT_EQ(face.name(), "'face' of [[boundary]] #2");
  face.vector3("point", required);
  const SceneError e = scene_error([&] { face.vector3("normal", required); });
  EXPECT_STREQ(e.what(),
               "scene.toml:5: missing required key 'normal' in 'face' of [[boundary]] #2; found "
               "'nrmal' on line 5: a misspelling?");
  // A single [boundary] table where entries are expected.
  Document single("[boundary]\nface = \"v0\"\n");
  EXPECT_STREQ(scene_error([&] { single.root.tables("boundary"); }).what(),
               "scene.toml:1: 'boundary' must be an array of tables (write each entry as "
               "[[boundary]]), got a table");
}

TEST(SceneReader, DottedSettingErrorsLandOnTheNestedKey) {
  const std::string text =
      "[geometry]\n"
      "iges = \"a.igs\"\n"
      "[geometry.refine]\n"
      "degree_elevation = [0, 11, 0]\n";
  Document d(text);
  SceneTable geometry = d.root.table("geometry", required);
  const SceneError e = scene_error([&] {
    geometry.fail(
        InvalidSetting("refine.degree_elevation", "element 2 must be in [0, 10] (got 11)"));
  });
  EXPECT_STREQ(e.what(),
               "scene.toml:4: 'degree_elevation' in [geometry.refine] element 2 must be in [0, "
               "10] (got 11)");
  // A key that is not in the file falls back to the table's line.
  const SceneError f = scene_error([&] { geometry.fail(InvalidSetting("surface", "x")); });
  EXPECT_EQ(f.line(), 1);
}

TEST(SceneReader, ForbiddenAndFreeFormKeys) {
  Document d("[material.parameters]\nsigma0 = 7e5\nb = 23.46\nc = 379\n");
  SceneTable material = d.root.table("material", required);
  SceneTable parameters = material.table("parameters", required);
  EXPECT_EQ(parameters.name(), "[material.parameters]");
  EXPECT_EQ(parameters.keys(), (std::vector<std::string>{"sigma0", "b", "c"}));
  EXPECT_STREQ(scene_error([&] { parameters.forbid("c", "is not used here"); }).what(),
               "scene.toml:4: 'c' in [material.parameters] is not used here");
  parameters.number("sigma0", required);
  parameters.number("b", required);
  EXPECT_NO_THROW(parameters.finish());
  EXPECT_NO_THROW(material.finish());
  EXPECT_NO_THROW(d.root.finish());
}

TEST(SceneReader, MissingFileIsASceneError) {
  const auto dir = testing_util::fresh_directory("missing");
  const SceneError e = scene_error([&] { (void)parse_toml_file(dir / "none.toml"); });
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.message(), "no such scene file");
}

TEST(SettingCheck, NumbersRangesAndDistances) {
  EXPECT_EQ(format_number(-0.001), "-0.001");
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(7e5), "700000");
  EXPECT_EQ(format_number(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(Range::positive().describe(), "> 0");
  EXPECT_EQ(Range::non_negative().describe(), ">= 0");
  EXPECT_EQ((Range{0.0, 1.0, true, false}).describe(), "in (0, 1]");
  EXPECT_EQ(Range{}.describe(), "");
  EXPECT_TRUE(Range::positive().contains(1e-300));
  EXPECT_FALSE(Range::positive().contains(0.0));
  EXPECT_FALSE(Range{}.contains(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(edit_distance("materal", "material"), 1u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(closest_match("tolerence", {"tolerance", "tangent"}), "tolerance");
  EXPECT_EQ(closest_match("x", {"u", "v"}), "");
  EXPECT_TRUE(is_plain_name("tip_z-2.5"));
  EXPECT_FALSE(is_plain_name(""));
  EXPECT_FALSE(is_plain_name("a b"));
  EXPECT_FALSE(is_plain_name("J/x"));
  try {
    check_range("dt", -0.001, Range::positive());
    ADD_FAILURE() << "no throw";
  } catch (const InvalidSetting& e) {
    EXPECT_STREQ(e.what(), "'dt' must be > 0 (got -0.001)");
    EXPECT_EQ(e.key(), "dt");
  }
}

}  // namespace
}  // namespace isomuscle::io

// Deck declaration, parsing and validation (include/mote/core/deck.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "mote/core/deck.hpp"

using mote::core::Deck;
using mote::core::DeckError;
using mote::core::DeckSchema;

namespace {

DeckSchema make_schema() {
  DeckSchema s;
  s.table("grid", "grid");
  s.integer("grid.nx").default_value(64LL).min(1).doc("cells");
  s.real("grid.length").greater_than(0.0).unit("cm").doc("size");
  s.string("grid.kind").default_value(std::string("uniform")).one_of({"uniform", "log"});
  s.boolean("grid.periodic").default_value(true);
  s.real_array("grid.sizes").default_value(std::vector<double>{1.0, 2.0}).min(0.0);
  s.table("dust", "dust physics", /*optional=*/true);
  s.real("dust.grain_size").greater_than(0.0).unit("cm");
  return s;
}

/// The message of the DeckError thrown by parsing `text`.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  const auto schema = make_schema();
  try {
    Deck::parse(text, "test.toml", schema, overrides);
  } catch (const DeckError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Deck, DefaultsAndValues) {
  const auto schema = make_schema();
  const auto d = Deck::parse("[grid]\nlength = 2\nsizes = [1, 2.5]\n", "t.toml", schema);
  EXPECT_EQ(d.integer("grid.nx"), 64);
  EXPECT_DOUBLE_EQ(d.real("grid.length"), 2.0);  // integer literal accepted for a real key
  EXPECT_EQ(d.string("grid.kind"), "uniform");
  EXPECT_TRUE(d.boolean("grid.periodic"));
  EXPECT_EQ(d.real_array("grid.sizes"), (std::vector<double>{1.0, 2.5}));
  EXPECT_FALSE(d.has_table("dust"));
}

TEST(Deck, UnknownKeyNamesLineAndSuggests) {
  const auto msg = error_of("[grid]\nlength = 1.0\nnxx = 3\n");
  EXPECT_NE(msg.find("test.toml:3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown key 'grid.nxx'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("did you mean 'grid.nx'"), std::string::npos) << msg;
}

TEST(Deck, UnknownTableSuggests) {
  const auto msg = error_of("[grd]\nlength = 1.0\n");
  EXPECT_NE(msg.find("unknown table [grd]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("did you mean [grid]"), std::string::npos) << msg;
}

TEST(Deck, WrongTypeIsRejected) {
  const auto msg = error_of("[grid]\nlength = 1.0\nnx = 2.5\n");
  EXPECT_NE(msg.find("test.toml:3: key 'grid.nx': expected integer"), std::string::npos) << msg;
  EXPECT_NE(msg.find("got real 2.5"), std::string::npos) << msg;
  EXPECT_NE(error_of("[grid]\nlength = \"big\"\n").find("expected real > 0 [cm], got string \"big\""),
            std::string::npos);
}

TEST(Deck, OutOfRangeIsRejected) {
  EXPECT_NE(error_of("[grid]\nlength = 1.0\nnx = -4\n")
                .find("key 'grid.nx': value -4 is out of range; expected integer >= 1"),
            std::string::npos);
  EXPECT_NE(error_of("[grid]\nlength = 0.0\n").find("expected real > 0"), std::string::npos);
  EXPECT_NE(error_of("[grid]\nlength = 1.0\nkind = \"cubic\"\n").find("one of \"uniform\", \"log\""),
            std::string::npos);
  EXPECT_NE(error_of("[grid]\nlength = 1.0\nsizes = [1.0, -1.0]\n").find("grid.sizes"), std::string::npos);
}

TEST(Deck, MissingRequiredKey) {
  const auto msg = error_of("[grid]\nnx = 4\n");
  EXPECT_NE(msg.find("missing required key 'grid.length'"), std::string::npos) << msg;
}

TEST(Deck, OptionalTableRequiredOnlyWhenPresent) {
  EXPECT_EQ(error_of("[grid]\nlength = 1.0\n"), "");
  EXPECT_NE(error_of("[grid]\nlength = 1.0\n[dust]\n").find("missing required key 'dust.grain_size'"),
            std::string::npos);
  const auto schema = make_schema();
  const auto d = Deck::parse("[grid]\nlength = 1.0\n[dust]\ngrain_size = 0.1\n", "t.toml", schema);
  EXPECT_TRUE(d.has_table("dust"));
  EXPECT_DOUBLE_EQ(d.real("dust.grain_size"), 0.1);
}

TEST(Deck, AllErrorsReportedTogether) {
  const auto msg = error_of("[grid]\nnx = 0\nfoo = 1\n");
  EXPECT_NE(msg.find("3 errors"), std::string::npos) << msg;
}

TEST(Deck, CommandLineOverrides) {
  const auto schema = make_schema();
  const auto d =
      Deck::parse("[grid]\nlength = 1.0\n", "t.toml", schema, {"grid.nx=128", "grid.kind=log", "dust.grain_size=1e-4"});
  EXPECT_EQ(d.integer("grid.nx"), 128);
  EXPECT_EQ(d.string("grid.kind"), "log");  // bare word taken as a string
  EXPECT_TRUE(d.has_table("dust"));         // an override can switch a table on
  const auto msg = error_of("[grid]\nlength = 1.0\n", {"grid.nx=-3"});
  EXPECT_NE(msg.find("command line 'grid.nx=-3'"), std::string::npos) << msg;
  EXPECT_NE(error_of("[grid]\nlength = 1.0\n", {"nx=3"}).find("table.key=value"), std::string::npos);
  // A value that is not TOML is a string only for a string key: for a number it is named as not a value.
  const auto huge = error_of("[grid]\nlength = 1.0\n", {"grid.length=1e400"});
  EXPECT_NE(huge.find("command line 'grid.length=1e400': key 'grid.length': '1e400' is not a TOML value (expected "
                      "real > 0 [cm]"),
            std::string::npos)
      << huge;
  EXPECT_NE(huge.find("(1 error)"), std::string::npos) << huge;  // not also "missing required key"
}

TEST(Deck, SyntaxErrorAndUnreadableFile) {
  EXPECT_NE(error_of("[grid\nlength = 1.0\n").find("TOML syntax error"), std::string::npos);
  const auto schema = make_schema();
  try {
    Deck::load("/nonexistent/deck.toml", schema);
    FAIL() << "no error for a missing file";
  } catch (const DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read deck file '/nonexistent/deck.toml'"), std::string::npos);
  }
}

TEST(Deck, ResolvedDeckReadsBackIdentically) {
  const auto schema = make_schema();
  const auto d = Deck::parse("[grid]\nlength = 0.1\n[dust]\ngrain_size = 3e-5\n", "t.toml", schema);
  const auto again = Deck::parse(d.to_toml(), "resolved", schema);
  EXPECT_EQ(again.to_toml().substr(again.to_toml().find('\n')), d.to_toml().substr(d.to_toml().find('\n')));
  EXPECT_EQ(again.real("grid.length"), 0.1);  // exact round trip of reals
  EXPECT_EQ(again.real("dust.grain_size"), 3e-5);
}

// A string with control characters (a path with a newline, a tab, an escape) is written escaped, so
// that the resolved deck each checkpoint stores reads back as the same value.
TEST(Deck, StringsWithControlCharactersReadBackIdentically) {
  auto schema = make_schema();
  schema.string("grid.label").default_value(std::string());
  const std::string label = std::string("a\nb\tc\"d\\e\x01f\x7fg\rh") + "\xc3\xa9";
  const auto d = Deck::parse("[grid]\nlength = 1\n", "t.toml", schema, {"grid.label=" + label});
  EXPECT_EQ(d.string("grid.label"), label);
  EXPECT_EQ(Deck::parse(d.to_toml(), "resolved", schema).string("grid.label"), label);
}

TEST(DeckSchema, EditDistanceAndHelp) {
  EXPECT_EQ(mote::core::edit_distance("kitten", "sitting"), 3);
  EXPECT_EQ(mote::core::edit_distance("", "abc"), 3);
  const auto schema = make_schema();
  const auto help = schema.help_text();
  EXPECT_NE(help.find("length (real)  required  [cm]  > 0"), std::string::npos) << help;
  EXPECT_NE(schema.markdown().find("| `nx` | integer | `64` |"), std::string::npos);
  EXPECT_THROW(make_schema().real("grid.nx"), std::logic_error);  // declared twice
}

// docs.deck_reference fails a problem whose --deck-reference finds these.
TEST(DeckSchema, UndocumentedEntriesAreListed) {
  const std::vector<std::string> expected = {"grid.kind", "grid.periodic", "grid.sizes", "dust.grain_size"};
  EXPECT_EQ(make_schema().undocumented(), expected);
  DeckSchema s;
  s.table("run", " ");
  s.real("run.t_end").doc("End time.");
  EXPECT_EQ(s.undocumented(), std::vector<std::string>{"[run]"});
}

// Issue 22: numbers that parse but cannot be run.
TEST(Deck, NonFiniteRealsAreRejectedUnlessAllowed) {
  const auto in_file = error_of("[grid]\nlength = inf\n");
  EXPECT_NE(in_file.find("test.toml:2: key 'grid.length': value inf is not finite"), std::string::npos) << in_file;
  const auto on_line = error_of("[grid]\nlength = 1.0\n", {"grid.length=nan", "grid.sizes=[1.0, -inf]"});
  EXPECT_NE(on_line.find("command line 'grid.length=nan': key 'grid.length': value nan is not finite"),
            std::string::npos)
      << on_line;
  EXPECT_NE(on_line.find("key 'grid.sizes': value [1.0, -inf] holds a value that is not finite"), std::string::npos)
      << on_line;
  DeckSchema schema;
  schema.table("run", "run");
  schema.real("run.limit").default_value(0.0).allow_non_finite();
  EXPECT_TRUE(std::isinf(Deck::parse("[run]\nlimit = inf\n", "t.toml", schema).real("run.limit")));
}

TEST(Deck, IntegersMustFitTheirCppType) {
  const auto msg = error_of("[grid]\nlength = 1.0\n", {"grid.nx=3000000000"});
  EXPECT_NE(msg.find("command line 'grid.nx=3000000000': key 'grid.nx': value 3000000000 does not fit the key's C++ "
                     "type int (-2147483648 to 2147483647); expected integer >= 1"),
            std::string::npos)
      << msg;
  DeckSchema schema;
  schema.table("run", "run");
  schema.integer("run.steps").int64().default_value(0LL);
  EXPECT_EQ(Deck::parse("[run]\nsteps = 3000000000\n", "t.toml", schema).integer("run.steps"), 3000000000LL);
}

TEST(Deck, TypeErrorOnRequiredKeyIsNotAlsoMissing) {
  const auto msg = error_of("[grid]\nlength = \"long\"\n");
  EXPECT_NE(msg.find("key 'grid.length': expected real"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("missing required key"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(1 error)"), std::string::npos) << msg;
}

TEST(Deck, DirectoryIsNotADeck) {
  const auto schema = make_schema();
  const std::string dir = ::testing::TempDir();
  try {
    Deck::load(dir, schema);
    ADD_FAILURE() << "a directory was read as a deck";
  } catch (const DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("'" + dir + "': is a directory"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("missing"), std::string::npos) << e.what();
  }
}

// Cross-key rules: every broken rule is reported with the line of its key,
// together with the keys' own errors; a rule that reads a rejected key is skipped.
TEST(Deck, CrossKeyRulesReportEveryErrorWithItsLine) {
  auto schema = make_schema();
  schema.rule([](const Deck& d, mote::core::DeckCheck& check) {
    if (d.real_array("grid.sizes").size() != static_cast<size_t>(d.integer("grid.nx")))
      check.fail("grid.sizes", "needs one value per cell (" + check.quote("grid.nx") + ")");
  });
  schema.rule([](const Deck& d, mote::core::DeckCheck& check) {
    if (d.string("grid.kind") == "log" && !(d.real("grid.length") > 1.0)) check.fail("grid.length", "must exceed 1");
  });
  const auto both = [&] {
    try {
      Deck::parse("[grid]\nnx = 3\nlength = 0.5\nkind = \"log\"\nsizes = [1.0]\n", "test.toml", schema);
    } catch (const DeckError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(both.find("(2 errors)"), std::string::npos) << both;
  EXPECT_NE(both.find("test.toml:5: key 'grid.sizes': needs one value per cell (grid.nx = 3 (test.toml:2))"),
            std::string::npos)
      << both;
  EXPECT_NE(both.find("test.toml:3: key 'grid.length': must exceed 1"), std::string::npos) << both;
  const auto with_bad_key = [&] {
    try {
      Deck::parse("[grid]\nnx = \"three\"\nlength = 0.5\nkind = \"log\"\n", "test.toml", schema);
    } catch (const DeckError& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(with_bad_key.find("(2 errors)"), std::string::npos) << with_bad_key;  // nx's own, and the length rule
  EXPECT_NE(with_bad_key.find("test.toml:3: key 'grid.length': must exceed 1"), std::string::npos) << with_bad_key;
  EXPECT_EQ(with_bad_key.find("grid.sizes"), std::string::npos) << with_bad_key;
}

// A rule that reads a key of an optional table the deck lacks is skipped where the missing table is
// reported (whatever the rules' order), and is a logic error (a missing has_table guard) where nothing
// reports it: the fld_benchmarks deck without [radiation] ended in std::terminate before.
TEST(Deck, RuleReadingAnAbsentOptionalTableIsSkippedWhenTheTableIsReported) {
  const auto reads_dust = [](const Deck& d, mote::core::DeckCheck& check) {
    if (d.integer("grid.nx") > 10 && d.real("dust.grain_size") > 1.0) check.fail("dust.grain_size", "too big");
  };
  const auto requires_dust = [](const Deck& d, mote::core::DeckCheck& check) {
    if (!d.has_table("dust")) check.fail_missing_table("dust", "the test needs it");
  };
  for (const bool reader_first : {true, false}) {
    auto schema = make_schema();
    if (reader_first) schema.rule(reads_dust);
    schema.rule(requires_dust);
    if (!reader_first) schema.rule(reads_dust);
    std::string why;
    try {
      Deck::parse("[grid]\nlength = 1\n", "test.toml", schema);
    } catch (const DeckError& e) {
      why = e.what();
    }
    EXPECT_NE(why.find("test.toml: missing table [dust]: the test needs it"), std::string::npos) << why;
    EXPECT_EQ(why.find("errors)"), std::string::npos) << why;  // one error
  }
  auto unguarded = make_schema();
  unguarded.rule(reads_dust);
  EXPECT_THROW(Deck::parse("[grid]\nlength = 1\n", "test.toml", unguarded), std::logic_error);
  EXPECT_NO_THROW(Deck::parse("[grid]\nlength = 1\n[dust]\ngrain_size = 0.5\n", "test.toml", unguarded));
}

TEST(ExitCodes, FollowTheKindOfFailure) {
  using namespace mote::core;
  EXPECT_EQ(exit_code_of(DeckError("x")), 2);
  EXPECT_EQ(exit_code_of(InputError("x")), 2);
  EXPECT_EQ(exit_code_of(NumericalError("x")), 3);
  EXPECT_EQ(exit_code_of(IOError("x")), 5);
  EXPECT_EQ(exit_code_of(std::runtime_error("x")), 1);
}

// Issue 22: a restart compares decks key by key; restart_mutable keys are marked as such.
TEST(Deck, ChangesToNameEveryDifferingKey) {
  DeckSchema s = make_schema();
  s.table("run", "run");
  s.real("run.t_end").default_value(1.0).restart_mutable();
  const Deck stored = Deck::parse("[grid]\nlength = 2.0\n", "a.toml", s);
  EXPECT_TRUE(stored.changes_to(Deck::parse("[grid]\nlength = 2.0\nnx = 64\n", "b.toml", s)).empty());
  const Deck given = Deck::parse("[grid]\nlength = 3.0\n[run]\nt_end = 5.0\n[dust]\ngrain_size = 0.1\n", "c.toml", s);
  const auto changes = stored.changes_to(given);
  ASSERT_EQ(changes.size(), 3u);
  EXPECT_EQ(changes[0].key, "grid.length");
  EXPECT_EQ(changes[0].before, "2.0");
  EXPECT_EQ(changes[0].after, "3.0");
  EXPECT_FALSE(changes[0].restart_mutable);
  EXPECT_EQ(changes[1].key, "dust.grain_size");
  EXPECT_EQ(changes[1].before, "(absent)");
  EXPECT_EQ(changes[2].key, "run.t_end");
  EXPECT_TRUE(changes[2].restart_mutable);
}

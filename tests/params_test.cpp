// Parameter schemas: defaults, parsing, ranges and the error messages users see.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "base/params.h"
#include "tests/error_of.h"

namespace oit {
namespace {

const ParamSchema kSchema = {
    ParamSpec::integer("k", 16, 1, 64, "slots per pixel"),
    ParamSpec::real("lambda", 0.05, 0.0, 1.0, "diffusion weight"),
    ParamSpec::boolean("early_exit", true, "stop when a pass is empty"),
    ParamSpec::choice("tail", "drop", {"drop", "blend"}, "what happens beyond k"),
};

std::string error_of(const RawParams& raw) {
  return test::error_of([&] { ParamSet set(kSchema, raw, "technique 'kbuffer'"); });
}

TEST(Params, DefaultsFillEveryKeyInSchemaOrder) {
  const ParamSet set(kSchema, {}, "t");
  EXPECT_EQ(set.integer("k"), 16);
  EXPECT_DOUBLE_EQ(set.real("lambda"), 0.05);
  EXPECT_TRUE(set.boolean("early_exit"));
  EXPECT_EQ(set.choice("tail"), "drop");
  EXPECT_EQ(set.canonical(), "k=16 lambda=0.05 early_exit=true tail=drop");
}

TEST(Params, ParsesUserText) {
  const ParamSet set(kSchema, {{"k", "64"}, {"lambda", "1e-1"}, {"early_exit", "off"}, {"tail", "blend"}}, "t");
  EXPECT_EQ(set.integer("k"), 64);
  EXPECT_DOUBLE_EQ(set.real("lambda"), 0.1);
  EXPECT_FALSE(set.boolean("early_exit"));
  EXPECT_EQ(set.choice("tail"), "blend");
}

TEST(Params, UnknownKeyNamesTheKeyAndTheKnownOnes) {
  const std::string message = error_of({{"kk", "3"}});
  EXPECT_NE(message.find("kk"), std::string::npos) << message;
  EXPECT_NE(message.find("technique 'kbuffer'"), std::string::npos) << message;
  EXPECT_NE(message.find("tail"), std::string::npos) << message;
}

TEST(Params, OutOfRangeValueNamesKeyValueAndRange) {
  const std::string message = error_of({{"k", "65"}});
  EXPECT_NE(message.find("'k'"), std::string::npos) << message;
  EXPECT_NE(message.find("65"), std::string::npos) << message;
  EXPECT_NE(message.find("[1, 64]"), std::string::npos) << message;
  EXPECT_NE(error_of({{"k", "0"}}), "");
  EXPECT_NE(error_of({{"lambda", "1.5"}}), "");
}

TEST(Params, MalformedValuesAreRejected) {
  for (const RawParams& raw : std::vector<RawParams>{{{"k", "16x"}},
                                                     {{"k", "1.5"}},
                                                     {{"k", ""}},
                                                     {{"lambda", "nan"}},
                                                     {{"lambda", "abc"}},
                                                     {{"early_exit", "maybe"}},
                                                     {{"tail", "keep"}}}) {
    const std::string message = error_of(raw);
    EXPECT_NE(message.find(raw.begin()->first), std::string::npos) << "accepted " << raw.begin()->second;
  }
  EXPECT_NE(error_of({{"tail", "keep"}}).find("{drop, blend}"), std::string::npos);
}

enum class Tail { drop, blend };
const Choices<Tail> kTails{{Tail::drop, "drop"}, {Tail::blend, "blend"}};

TEST(Params, ChoicesBuildTheSpecAndReadBackTheValue) {
  const ParamSpec spec = kTails.spec("tail", Tail::blend, "what happens beyond k");
  EXPECT_EQ(spec.type, ParamType::choice);
  EXPECT_EQ(spec.default_value, "blend");
  EXPECT_EQ(spec.choices, (std::vector<std::string>{"drop", "blend"}));
  EXPECT_EQ(spec.range_text(), "one of {drop, blend}");
  const ParamSchema schema = {spec};
  EXPECT_EQ(ParamSet(schema, {}, "t").choice("tail", kTails), Tail::blend);
  const ParamSet set(schema, {{"tail", "drop"}}, "t");
  EXPECT_EQ(set.choice("tail", kTails), Tail::drop);
  EXPECT_EQ(set.canonical(), "tail=drop");  // the text, as before the table
  EXPECT_STREQ(kTails.name(Tail::blend), "blend");
  EXPECT_EQ(kTails.names(), (std::vector<std::string>{"drop", "blend"}));
  // Numbers are choices too (a sample count): the value is the number.
  const Choices<int> samples{{4, "4"}, {8, "8"}};
  EXPECT_EQ(ParamSet({samples.spec("samples", 4, "")}, {{"samples", "8"}}, "t").choice("samples", samples), 8);
}

TEST(Params, ChoicesNameWhatTheyLack) {
  try {
    kTails.value("keep");
    FAIL() << "accepted keep";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "'keep' is not one of {drop, blend}");
  }
  // A schema built without the table: reading it through the table is a programming error that names the owner.
  const ParamSet set(kSchema, {{"tail", "blend"}}, "technique 'kbuffer'");
  const Choices<Tail> other{{Tail::drop, "drop"}};
  try {
    set.choice("tail", other);
    FAIL() << "read blend through a table without it";
  } catch (const std::logic_error& e) {
    EXPECT_EQ(std::string(e.what()), "technique 'kbuffer': parameter 'tail' = 'blend' is not in the table it is read with");
  }
}

TEST(Params, AssignmentParsing) {
  RawParams raw;
  parse_assignment("k=8", raw);
  parse_assignment("tail=blend", raw);
  EXPECT_EQ(raw.at("k"), "8");
  EXPECT_EQ(raw.at("tail"), "blend");
  EXPECT_THROW(parse_assignment("k", raw), std::invalid_argument);
  EXPECT_THROW(parse_assignment("=3", raw), std::invalid_argument);
}

TEST(Params, AskingForAnUndeclaredParameterIsAProgrammingError) {
  const ParamSet set(kSchema, {}, "t");
  EXPECT_ANY_THROW(set.integer("missing"));
  EXPECT_ANY_THROW(set.real("k"));  // wrong type
}

TEST(Params, IntegerOrAutoAcceptsAutoAndNumbersInRange) {
  const ParamSchema schema = {ParamSpec::integer_or_auto("k", "auto", 1, 64, "slots per pixel")};
  const ParamSet automatic(schema, {}, "t");
  EXPECT_TRUE(automatic.is_auto("k"));
  EXPECT_EQ(automatic.canonical(), "k=auto");
  EXPECT_THROW(automatic.integer("k"), std::logic_error);
  const ParamSet fixed(schema, {{"k", "8"}}, "t");
  EXPECT_FALSE(fixed.is_auto("k"));
  EXPECT_EQ(fixed.integer("k"), 8);
  try {
    ParamSet bad(schema, {{"k", "65"}}, "technique 'kbuffer'");
    FAIL() << "k=65 was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("integer in [1, 64] or auto"), std::string::npos) << e.what();
  }
  // A plain integer parameter still refuses "auto".
  EXPECT_THROW(ParamSet(kSchema, {{"k", "auto"}}, "t"), std::invalid_argument);
}

TEST(Params, PathIsEmptyOrAReadableFileWithoutSeparators) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("oit_params_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string file = (dir / "table.txt").string();
  std::ofstream(file) << "1\n";
  const ParamSchema schema = {ParamSpec::path("table", "", "a table")};
  const ParamSet unset(schema, {}, "t");
  EXPECT_EQ(unset.path("table"), "");
  EXPECT_EQ(unset.canonical(), "table=");
  const ParamSet set(schema, {{"table", file}}, "t");
  EXPECT_EQ(set.path("table"), file);
  EXPECT_EQ(set.canonical(), "table=" + file);
  // The canonical text reads back through the same assignment parser.
  RawParams again;
  parse_assignment(set.canonical(), again);
  EXPECT_EQ(ParamSet(schema, again, "t").path("table"), file);

  auto message = [&](const std::string& path) {
    try {
      ParamSet bad(schema, {{"table", path}}, "technique 'x'");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string missing = (dir / "missing.txt").string();
  for (const auto& [path, why] : {std::pair{missing, "does not exist"},
                                  std::pair{std::string("missing.txt"), "relative to"},
                                  std::pair{dir.string(), "is a directory"},
                                  std::pair{(dir / "a b.txt").string(), "whitespace"},
                                  std::pair{(dir / "a,b.txt").string(), "','"},
                                  std::pair{(dir / "a=b.txt").string(), "'='"}}) {
    const std::string text = message(path);
    EXPECT_NE(text.find("'table'"), std::string::npos) << text;
    EXPECT_NE(text.find(path), std::string::npos) << text;
    EXPECT_NE(text.find(why), std::string::npos) << text;
  }
  fs::remove_all(dir);
  EXPECT_NE(schema[0].range_text().find("path"), std::string::npos);
}

}  // namespace
}  // namespace oit

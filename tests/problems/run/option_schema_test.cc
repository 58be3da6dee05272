#include "gproj/problems/run/option_schema.h"

#include <gtest/gtest.h>

#include <cmath>

namespace gproj {
namespace {

OptionSpec Spec(OptionType type) {
  OptionSpec spec;
  spec.name = "value";
  spec.type = type;
  return spec;
}

// The rule an OptionError names, or "" when the value passes.
template <typename Check>
std::string RuleOf(Check check) {
  try {
    check();
  } catch (const OptionError& e) {
    EXPECT_EQ(std::string(e.what()), e.option() + ": " + e.rule());
    return e.rule();
  }
  return "";
}

TEST(OptionSchemaTest, NumbersAreFiniteAndWithinTheirRange) {
  OptionSpec spec = Spec(OptionType::kNumber);
  spec.min = 0.0, spec.min_exclusive = true;
  EXPECT_EQ(CheckOptionValue(spec, 0.5), nlohmann::json(0.5));
  EXPECT_EQ(CheckOptionValue(spec, 2).get<double>(), 2.0);  // an integer is a number
  EXPECT_TRUE(CheckOptionValue(spec, 2).is_number_float());
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(spec, 0.0); }), "0 is not > 0");
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(spec, std::nan("")); }), "nan is not a finite number");
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(spec, "1"); }), "1 is not a number");
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(spec, true); }), "true is not a number");
  spec.min = 1e-12, spec.max = 1.0, spec.min_exclusive = false;
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(spec, 2.0); }), "2 is not in [1e-12, 1]");
  spec.max_exclusive = true;
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(spec, 1.0); }), "1 is not in [1e-12, 1)");
}

TEST(OptionSchemaTest, TextIsDecimalAndWhole) {
  OptionSpec number = Spec(OptionType::kNumber);
  EXPECT_EQ(ParseOptionText(number, "1e-3").get<double>(), 1e-3);
  for (const char* bad : {"0x10", "1.5x", "inf", "nan", "one"})
    EXPECT_EQ(RuleOf([&] { ParseOptionText(number, bad); }),
              std::string(bad) + " is not a finite number")
        << bad;
  EXPECT_EQ(RuleOf([&] { ParseOptionText(number, ""); }), "an empty value is not allowed");
  OptionSpec integer = Spec(OptionType::kInt);
  integer.min = 0, integer.max = 10;
  EXPECT_EQ(ParseOptionText(integer, "7"), nlohmann::json(7));
  EXPECT_EQ(RuleOf([&] { ParseOptionText(integer, "2.5"); }), "2.5 is not an integer");
  EXPECT_EQ(RuleOf([&] { ParseOptionText(integer, "1e3"); }), "1e3 is not an integer");
  EXPECT_EQ(RuleOf([&] { ParseOptionText(integer, "11"); }), "11 is not in [0, 10]");
}

TEST(OptionSchemaTest, ChoicesListsAndSwitches) {
  OptionSpec choice = Spec(OptionType::kChoice);
  choice.choices = {"gp", "ceres"};
  EXPECT_EQ(ParseOptionText(choice, "ceres"), nlohmann::json("ceres"));
  EXPECT_EQ(RuleOf([&] { ParseOptionText(choice, "newton"); }), "'newton' is not one of gp, ceres");
  OptionSpec list = Spec(OptionType::kNumbers);
  list.count = 2, list.placeholder = "MIN,MAX", list.min = 0.0;
  EXPECT_EQ(ParseOptionText(list, "0.01,5"), nlohmann::json({0.01, 5.0}));
  EXPECT_EQ(RuleOf([&] { ParseOptionText(list, "1,2,3"); }), "expects 2 numbers (MIN,MAX), not 3");
  EXPECT_EQ(RuleOf([&] { ParseOptionText(list, "1,-2"); }), "-2 is not >= 0");
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(list, 0.2); }), "0.2 is not a list of numbers");
  OptionSpec flag = Spec(OptionType::kBool);
  EXPECT_EQ(CheckOptionValue(flag, false), nlohmann::json(false));
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(flag, 1); }), "1 is not true or false");
}

// Points are (n, 3): a transposed (3, n) list is refused, never read in the wrong order.
TEST(OptionSchemaTest, PointsAreTriplesInTheirOrder) {
  OptionSpec points = Spec(OptionType::kPoints);
  points.count = 2, points.placeholder = "P1,P2";
  EXPECT_EQ(ParseOptionText(points, "1,2,3,4,5,6"),
            nlohmann::json({{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}}));
  EXPECT_EQ(CheckOptionValue(points, {{1, 2, 3}, {4, 5, 6}}),
            nlohmann::json({{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}}));
  EXPECT_EQ(RuleOf([&] {
              CheckOptionValue(points, {{1, 4}, {2, 5}, {3, 6}});
            }),
            "expects 2 points (P1,P2), not 3");
  OptionSpec any = Spec(OptionType::kPoints);
  EXPECT_EQ(RuleOf([&] {
              CheckOptionValue(any, {{1, 4}, {2, 5}, {3, 6}});
            }),
            "point 0 is not three numbers x, y, z (it has 2)");
  EXPECT_EQ(RuleOf([&] { ParseOptionText(points, "1,2,3,4,5"); }),
            "expects 6 comma-separated numbers (P1,P2), not 5");
  EXPECT_EQ(RuleOf([&] {
              CheckOptionValue(any, {1, 2, 3});
            }),
            "point 0 is not three numbers x, y, z");
}

// Vertex values: "ID:VALUE" words, pairs or an object of ids; ids whole, once, values in range.
TEST(OptionSchemaTest, VertexValuesArePairsOfAnIdAndAValue) {
  OptionSpec hold = Spec(OptionType::kVertexValues);
  hold.min = -10.0;
  const nlohmann::json pairs = {{12, 0.5}, {3, -1.0}};
  EXPECT_EQ(ParseOptionText(hold, "12:0.5,3:-1"), pairs);
  EXPECT_EQ(CheckOptionValue(hold, {{12.0, 0.5}, {3, -1}}), pairs);
  const nlohmann::json object = {{"3", -1}, {"12", 0.5}};  // Python's {3: -1, 12: 0.5}
  ASSERT_TRUE(object.is_object());
  EXPECT_EQ(CheckOptionValue(hold, object), nlohmann::json({{3, -1.0}, {12, 0.5}}));  // by id
  EXPECT_EQ(OptionText(pairs), "12:0.5,3:-1");
  EXPECT_EQ(RuleOf([&] { ParseOptionText(hold, "12=0.5"); }),
            "'12=0.5' is not VERTEX:VALUE (e.g. 12:0.5)");
  EXPECT_EQ(RuleOf([&] { ParseOptionText(hold, "3x:1"); }), "3x is not an integer");
  EXPECT_EQ(RuleOf([&] { ParseOptionText(hold, "1:-11"); }), "-11 is not >= -10");
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(hold, {{-1, 0.0}}); }), "-1 is not in [0, 2000000000]");
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(hold, {{1.5, 0.0}}); }), "1.5 is not an integer");
  EXPECT_EQ(RuleOf([&] {
              CheckOptionValue(hold, {{1, 0.0}, {1, 2.0}});
            }),
            "vertex 1 is given twice");
  EXPECT_EQ(RuleOf([&] {
              CheckOptionValue(hold, {{1, 0.0, 3.0}});
            }),
            "entry 0 is not a pair [vertex, value]");
  EXPECT_EQ(RuleOf([&] { CheckOptionValue(hold, 3.0); }),
            "3 is not a list of [vertex, value] pairs");
}

TEST(OptionSchemaTest, CompleteOptionsFillsDefaultsAndRefusesUnknownNames) {
  OptionSpec tolerance = Spec(OptionType::kNumber);
  tolerance.name = "tolerance", tolerance.default_value = 1e-9, tolerance.min = 0.0;
  OptionSpec bounds = Spec(OptionType::kNumbers);
  bounds.name = "edge_length";  // no default: absent unless given
  const std::vector<OptionSpec> specs = {tolerance, bounds};
  EXPECT_EQ(CompleteOptions(specs, nullptr), nlohmann::json({{"tolerance", 1e-9}}));
  EXPECT_EQ(CompleteOptions(specs, {{"tolerance", 1}}), nlohmann::json({{"tolerance", 1.0}}));
  try {
    CompleteOptions(specs, {{"tolerence", 1.0}});
    FAIL() << "a misspelt option was accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.option(), "tolerence");
    EXPECT_EQ(e.rule(), "there is no such option (did you mean tolerance?)");
    EXPECT_TRUE(e.type_mismatch());
  }
  EXPECT_EQ(RuleOf([&] { CompleteOptions(specs, {{"zzz", 1.0}}); }), "there is no such option");
}

struct Settings {
  double weight = 2.5;
  int order = 2;
  std::string method = "gp";
  bool flag = true;
};

TEST(OptionSchemaTest, FieldsTakeTheirDefaultsFromTheSettingsAndApplyValues) {
  OptionSchema<Settings> schema;
  schema.Field<double>("weight", OptionType::kNumber, "w",
                       [](Settings& s) -> double& { return s.weight; });
  schema.Field<int>("order", OptionType::kInt, "o", [](Settings& s) -> int& { return s.order; });
  schema
      .Field<std::string>("method", OptionType::kChoice, "m",
                          [](Settings& s) -> std::string& { return s.method; })
      .Choices({"gp", "ceres"});
  schema.Field<bool>("flag", OptionType::kBool, "f", [](Settings& s) -> bool& { return s.flag; });
  ASSERT_EQ(schema.specs().size(), 4u);
  EXPECT_EQ(schema.specs()[0].default_value, nlohmann::json(2.5));
  EXPECT_EQ(schema.specs()[1].default_value, nlohmann::json(2));
  EXPECT_EQ(schema.specs()[2].choices, (std::vector<std::string>{"gp", "ceres"}));
  const Settings s = schema.Apply(CompleteOptions(
      schema.specs(), {{"weight", 0.5}, {"order", 3}, {"method", "ceres"}, {"flag", false}}));
  EXPECT_EQ(s.weight, 0.5);
  EXPECT_EQ(s.order, 3);
  EXPECT_EQ(s.method, "ceres");
  EXPECT_FALSE(s.flag);
}

}  // namespace
}  // namespace gproj

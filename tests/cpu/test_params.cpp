// Parameters: --set parsing, ranges, unknown keys, the configuration dump.
#include <catch2/catch.hpp>

#include "core/util/error.h"
#include "core/util/params.h"

using namespace vplgi;

namespace {

struct Example {
    float exposure = 1.0f;
    int count = 64;
    bool enabled = false;
    std::uint32_t seed = 1;
    void visitParams(ParamVisitor& v)
    {
        v.field("x.exposure", exposure, 0.0f, 10.0f, "exposure");
        v.field("x.count", count, 1, 100, "count");
        v.field("x.enabled", enabled, "enabled");
        v.field("x.seed", seed, "seed");
    }
};

} // namespace

TEST_CASE("settings apply to the fields they name, later ones win", "[params]")
{
    Example e;
    ParamSetter setter(Settings{{"x.exposure", "2.5"}, {"x.count", "7"}, {"x.enabled", "true"}, {"x.count", "9"},
                        {"x.seed", "4000000000"}});
    e.visitParams(setter);
    REQUIRE_NOTHROW(setter.finish());
    CHECK(e.exposure == 2.5f);
    CHECK(e.count == 9);
    CHECK(e.enabled);
    CHECK(e.seed == 4000000000u);
}

TEST_CASE("bad settings are errors naming the key", "[params]")
{
    Example e;
    ParamSetter outside(Settings{{"x.count", "0"}});
    CHECK_THROWS_WITH(e.visitParams(outside), Catch::Contains("x.count = 0 is outside [1, 100]"));
    ParamSetter notNumber(Settings{{"x.exposure", "bright"}});
    CHECK_THROWS_WITH(e.visitParams(notNumber), Catch::Contains("x.exposure"));
    ParamSetter fraction(Settings{{"x.count", "2.5"}});
    CHECK_THROWS_WITH(e.visitParams(fraction), Catch::Contains("not an integer"));
    ParamSetter unknown(Settings{{"x.exposur", "1"}});
    e.visitParams(unknown);
    CHECK_THROWS_WITH(unknown.finish(), "unknown parameter \"x.exposur\" (did you mean \"x.exposure\"?)");
    // No likely typo: the keys of the same group, else every key.
    ParamSetter far(Settings{{"x.brightness", "1"}});
    e.visitParams(far);
    CHECK_THROWS_WITH(far.finish(), Catch::StartsWith("unknown parameter \"x.brightness\" (known: x."));
    ParamSetter otherGroup(Settings{{"nothing.here", "1"}});
    e.visitParams(otherGroup);
    CHECK_THROWS_WITH(otherGroup.finish(), Catch::StartsWith("unknown parameter \"nothing.here\" (known: x."));
    CHECK_THROWS_AS(parseSetting("novalue"), Error);
    CHECK(parseSetting("a.b=c=d").second == "c=d");
}

TEST_CASE("the dump lists every field with its value", "[params]")
{
    Example e;
    e.count = 12;
    ParamDumper dumper;
    e.visitParams(dumper);
    CHECK(dumper.values().at("x.count") == "12");
    CHECK(dumper.text().find("x.exposure = 1  # exposure [0, 10]") != std::string::npos);
}

TEST_CASE("a choice kept as its name: set by name or index, dumped, changes reported", "[params]")
{
    // The names are a run-time list (renderer.display: the technique's views are among them).
    const std::vector<std::string> names = {"final", "normal", "smcir.atlas"};
    std::string view = "final";
    auto visit = [&](ParamVisitor& v) { v.choice("x.view", view, names, "what to show"); };

    ParamSetter byName(Settings{{"x.view", "smcir.atlas"}});
    visit(byName);
    byName.finish();
    CHECK(view == "smcir.atlas");
    CHECK(byName.changedKeys().count("x.view") == 1);

    ParamSetter byIndex(Settings{{"x.view", "1"}});
    visit(byIndex);
    CHECK(view == "normal");

    ParamSetter same(Settings{{"x.view", "normal"}});
    visit(same);
    CHECK(same.changedKeys().empty());

    ParamDumper dumper;
    visit(dumper);
    CHECK(dumper.values().at("x.view") == "normal");
    CHECK(dumper.text().find("final|normal|smcir.atlas") != std::string::npos);

    ParamSetter bad(Settings{{"x.view", "bogus"}});
    CHECK_THROWS_WITH(visit(bad), Catch::Contains("x.view") && Catch::Contains("smcir.atlas"));
    CHECK(view == "normal");
    // A value outside the list is the owner's error, reported rather than dumped as garbage.
    view = "gone";
    ParamDumper stale;
    CHECK_THROWS_WITH(visit(stale), Catch::Contains("x.view") && Catch::Contains("gone"));
}

// The settings enums' name tables (core/enum_names.h): every spelling parses to its value and
// back, and the scene-format docs and the README document every spelling the parser takes.

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/scene.h"

namespace penumbra {
namespace {

std::string read_file(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

template <class E> void expect_round_trip() {
    for (const EnumName<E>& n : k_enum_names<E>) {
        ASSERT_TRUE(parse_enum<E>(n.name).has_value()) << n.name;
        EXPECT_EQ(*parse_enum<E>(n.name), n.value) << n.name;
        // The written name parses to the same value (an alias is written as its first name).
        EXPECT_EQ(*parse_enum<E>(enum_name(n.value)), n.value) << n.name;
    }
    EXPECT_FALSE(parse_enum<E>("no-such-name").has_value());
}

template <class E> void expect_documented(const std::string& doc, const char* file) {
    for (const EnumName<E>& n : k_enum_names<E>)
        EXPECT_NE(doc.find("`\"" + std::string(n.name) + "\"`"), std::string::npos)
            << file << " does not document '" << n.name << "'";
}

TEST(EnumNames, EverySpellingParsesToItsValueAndBack) {
    expect_round_trip<SolverMethod>();
    expect_round_trip<RefinementOracle>();
    expect_round_trip<Clustering>();
    expect_round_trip<SolverIteration>();
    expect_round_trip<PixelFilter>();
    expect_round_trip<LightmapMode>();
    EXPECT_EQ(parse_enum<SolverMethod>("gathering"), SolverMethod::gauss_seidel);
    EXPECT_EQ(enum_name(SolverMethod::gauss_seidel), "gauss_seidel");
    EXPECT_EQ(enum_name_list<Clustering>(), "auto, on, off");
}

TEST(EnumNames, SceneFormatDocumentsEverySpelling) {
    const std::string doc = read_file(PENUMBRA_SOURCE_DIR "/docs/scene-format.md");
    ASSERT_FALSE(doc.empty());
    expect_documented<SolverMethod>(doc, "docs/scene-format.md");
    expect_documented<RefinementOracle>(doc, "docs/scene-format.md");
    expect_documented<Clustering>(doc, "docs/scene-format.md");
    expect_documented<SolverIteration>(doc, "docs/scene-format.md");
    expect_documented<PixelFilter>(doc, "docs/scene-format.md");
    expect_documented<LightmapMode>(doc, "docs/scene-format.md");
}

TEST(EnumNames, ReadmeListsEveryCliChoice) {
    const std::string readme = read_file(PENUMBRA_SOURCE_DIR "/README.md");
    ASSERT_FALSE(readme.empty());
    for (const std::string& name : enum_names<SolverMethod>())
        EXPECT_NE(readme.find("`" + name + "`"), std::string::npos) << "--method " << name;
    for (const std::string& name : enum_names<Clustering>())
        EXPECT_NE(readme.find(name), std::string::npos) << "--clustering " << name;
    for (const std::string& name : enum_names<SolverIteration>())
        EXPECT_NE(readme.find(name), std::string::npos) << "--iteration " << name;
}

} // namespace
} // namespace penumbra

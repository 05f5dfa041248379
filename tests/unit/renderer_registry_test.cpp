// The renderer list and the option schemas (render/registry/): every row belongs to a family,
// names and flags are unique, and each option lands in its family's own Options struct and
// reads back what it set. GL-free: nothing here makes a renderer.
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "tellus/render/rag/rag_renderer.hpp"
#include "tellus/render/registry/renderer_registry.hpp"
#include "tellus/render/rings/rings_renderer.hpp"
#include "tellus/render/spiral/spiral_renderer.hpp"

namespace tellus {
namespace {

TEST(RendererRegistry, NamesAndFlagsAreUniqueAndEveryRowHasItsFamily) {
  std::set<std::string> names, flags;
  for (const RendererEntry* row : rendererTable()) {
    EXPECT_TRUE(names.insert(std::string(row->name)).second) << row->name;
    ASSERT_NE(findRendererFamily(familyNameOf(*row)), nullptr) << row->name;
    EXPECT_EQ(findRenderer(row->name), row);
    EXPECT_NE(row->create, nullptr) << row->name;
  }
  EXPECT_EQ(names.size(), 18u);
  for (const RendererFamily* family : rendererFamilies()) {
    for (const RendererOption& option : family->schema.options) {
      EXPECT_TRUE(option.flag.starts_with("--")) << option.flag;
      EXPECT_TRUE(flags.insert(option.flag).second) << option.flag;
      for (const std::string& alias : option.aliases) EXPECT_TRUE(flags.insert(alias).second) << alias;
      EXPECT_FALSE(option.help.empty()) << option.flag;
      EXPECT_FALSE(option.label.empty()) << option.flag;
    }
  }
}

// Each option's default reads back as its kind's value, within its range, and setting what
// was read changes nothing; a number set to the ends of its range reads back as set.
TEST(RendererRegistry, EveryOptionRoundTripsThroughItsFamilysOptions) {
  for (const RendererFamily* family : rendererFamilies()) {
    for (const RendererOption& option : family->schema.options) {
      std::any options = family->schema.defaults();
      const OptionValue initial = option.get(options);
      switch (option.kind) {
        case OptionKind::Integer: {
          ASSERT_TRUE(std::holds_alternative<std::int64_t>(initial)) << option.flag;
          const auto value = std::get<std::int64_t>(initial);
          if (!option.autoDefault) {
            EXPECT_GE(double(value), option.min) << option.flag;
            EXPECT_LE(double(value), option.max) << option.flag;
          }
          for (const double end : {option.min, option.max}) {
            option.set(options, std::int64_t(end));
            EXPECT_EQ(std::get<std::int64_t>(option.get(options)), std::int64_t(end)) << option.flag;
          }
          break;
        }
        case OptionKind::Real: {
          ASSERT_TRUE(std::holds_alternative<double>(initial)) << option.flag;
          if (!option.autoDefault) {
            EXPECT_GE(std::get<double>(initial), option.min) << option.flag;
            EXPECT_LE(std::get<double>(initial), option.max) << option.flag;
          }
          option.set(options, option.max);
          EXPECT_NEAR(std::get<double>(option.get(options)), option.max, option.max * 1e-6) << option.flag;
          break;
        }
        case OptionKind::Flag:
          ASSERT_TRUE(std::holds_alternative<bool>(initial)) << option.flag;
          EXPECT_FALSE(std::get<bool>(initial)) << option.flag << ": a flag is off by default";
          option.set(options, true);
          EXPECT_TRUE(std::get<bool>(option.get(options))) << option.flag;
          break;
        case OptionKind::Choice:
          ASSERT_TRUE(std::holds_alternative<std::string>(initial)) << option.flag;
          EXPECT_NE(std::find(option.choices.begin(), option.choices.end(),
                              std::get<std::string>(initial)),
                    option.choices.end())
              << option.flag;
          for (const std::string& choice : option.choices) {
            option.set(options, choice);
            EXPECT_EQ(std::get<std::string>(option.get(options)), choice) << option.flag;
          }
          break;
        case OptionKind::Choices:
        case OptionKind::Paths:
          ASSERT_TRUE(std::holds_alternative<std::vector<std::string>>(initial)) << option.flag;
          break;
        case OptionKind::Path:
          ASSERT_TRUE(std::holds_alternative<std::string>(initial)) << option.flag;
          break;
      }
      std::any again = family->schema.defaults();
      option.set(again, initial);
      EXPECT_EQ(formatOptionValue(option.get(again)), formatOptionValue(initial)) << option.flag;
    }
  }
}

const RendererOption& optionNamed(std::string_view flag) {
  for (const RendererFamily* family : rendererFamilies()) {
    for (const RendererOption& option : family->schema.options) {
      if (option.flag == flag) return option;
    }
  }
  throw std::out_of_range(std::string(flag));
}

// Where values land: the struct fields the renderers read, negated flags and unit conversions
// included.
TEST(RendererRegistry, OptionsLandInTheAlgorithmsOwnStructs) {
  RendererSettings settings;
  optionNamed("--rag-coarse").set(settings.of("rag"), std::int64_t(40));
  optionNamed("--rag-no-clip").set(settings.of("rag"), true);
  EXPECT_EQ(settings.as<RagOptions>("rag").coarseVertices, 40);
  EXPECT_FALSE(settings.as<RagOptions>("rag").refinement.earlyClip);
  optionNamed("--rings-count").set(settings.of("rings"), std::int64_t(3));
  optionNamed("--rings-patch-cells").set(settings.of("rings"), std::string("64"));
  EXPECT_EQ(settings.as<RingsOptions>("rings").rings, 3);
  EXPECT_EQ(settings.as<RingsOptions>("rings").patchCells, 64);
  optionNamed("--spiral-imagery-memory").set(settings.of("spiral"), std::int64_t(64));
  optionNamed("--spiral-without").set(settings.of("spiral"),
                                      std::vector<std::string>{"clouds", "bump"});
  const SpiralOptions& spiral = settings.as<SpiralOptions>("spiral");
  EXPECT_EQ(spiral.imageryOptions.quadtree.memoryBudgetBytes, std::uint64_t(64) << 20);
  EXPECT_EQ(spiral.features, std::uint32_t(kSpiralAllFeatures & ~kSpiralClouds & ~kSpiralBumpMapping));
  // The bench's record: every option of the family, by name.
  const std::map<std::string, OptionValue> values = rendererOptionValues("rag-right", settings);
  EXPECT_EQ(std::get<std::int64_t>(values.at("rag-coarse")), 40);
  EXPECT_TRUE(std::get<bool>(values.at("rag-no-clip")));
  EXPECT_EQ(values.size(), findRendererFamily("rag")->schema.options.size());
  EXPECT_THROW(settings.of("no-such-family"), std::out_of_range);
}

TEST(RendererRegistry, AFileBesideTheInputIsFoundByItsExtension) {
  const RendererOption& patches = optionNamed("--bdam-patches");
  RendererSettings settings;
  EXPECT_EQ(optionPathOrBesideInput(patches, settings.of("bdam"), "/data/korea.tstore"),
            std::filesystem::path("/data/korea.bdam"));
  EXPECT_EQ(optionPathOrBesideInput(patches, settings.of("bdam"), ""), std::filesystem::path());
  patches.set(settings.of("bdam"), std::string("/other/p.bdam"));
  EXPECT_EQ(optionPathOrBesideInput(patches, settings.of("bdam"), "/data/korea.tstore"),
            std::filesystem::path("/other/p.bdam"));
}

}  // namespace
}  // namespace tellus

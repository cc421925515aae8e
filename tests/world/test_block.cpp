#include <set>
#include <string>

#include <gtest/gtest.h>

#include "world/block.h"

namespace {

using world::BlockType;

TEST(Block, NamesRoundTripAndAreUnique) {
    std::set<std::string_view> names;
    for (int i = 0; i < world::kBlockTypeCount; ++i) {
        const auto t = static_cast<BlockType>(i);
        const auto& info = world::blockInfo(t);
        EXPECT_FALSE(info.name.empty());
        EXPECT_TRUE(names.insert(info.name).second) << info.name;
        ASSERT_TRUE(world::blockFromName(info.name).has_value()) << info.name;
        EXPECT_EQ(*world::blockFromName(info.name), t);
    }
    EXPECT_EQ(world::blockFromName("cobblestone"), BlockType::Cobblestone);
    EXPECT_EQ(world::blockFromName("gravel"), BlockType::Gravel);
    EXPECT_FALSE(world::blockFromName("Stone").has_value());
    EXPECT_FALSE(world::blockFromName("").has_value());
    EXPECT_FALSE(world::blockFromName("lava").has_value());
}

TEST(Block, SolidityMatchesTable) {
    for (int i = 0; i < world::kBlockTypeCount; ++i) {
        const auto t = static_cast<BlockType>(i);
        EXPECT_EQ(world::isSolid(t), world::blockInfo(t).solid) << world::blockInfo(t).name;
        EXPECT_EQ(world::isSolid(t), t != BlockType::Air);
    }
}

TEST(Block, AtlasTiles) {
    // The atlas layout in assets/README.md.
    const auto tiles = [](BlockType t) {
        const auto& i = world::blockInfo(t);
        return std::array<int, 3>{i.tileTop, i.tileSide, i.tileBottom};
    };
    EXPECT_EQ(tiles(BlockType::Grass), (std::array<int, 3>{0, 1, 2}));
    EXPECT_EQ(tiles(BlockType::Dirt), (std::array<int, 3>{2, 2, 2}));
    EXPECT_EQ(tiles(BlockType::Stone), (std::array<int, 3>{3, 3, 3}));
    EXPECT_EQ(tiles(BlockType::Sand), (std::array<int, 3>{4, 4, 4}));
    EXPECT_EQ(tiles(BlockType::Log), (std::array<int, 3>{6, 5, 6}));
    EXPECT_EQ(tiles(BlockType::Leaves), (std::array<int, 3>{7, 7, 7}));
    EXPECT_EQ(tiles(BlockType::Planks), (std::array<int, 3>{8, 8, 8}));
    EXPECT_EQ(tiles(BlockType::Brick), (std::array<int, 3>{9, 9, 9}));
    EXPECT_EQ(tiles(BlockType::Cobblestone), (std::array<int, 3>{10, 10, 10}));
    EXPECT_EQ(tiles(BlockType::Snow), (std::array<int, 3>{11, 12, 2}));
    EXPECT_EQ(tiles(BlockType::Gravel), (std::array<int, 3>{13, 13, 13}));
    EXPECT_EQ(tiles(BlockType::Lamp), (std::array<int, 3>{14, 14, 14}));
    EXPECT_EQ(tiles(BlockType::RedLamp), (std::array<int, 3>{15, 15, 15}));
    EXPECT_EQ(tiles(BlockType::GreenLamp), (std::array<int, 3>{16, 16, 16}));
    EXPECT_EQ(tiles(BlockType::BlueLamp), (std::array<int, 3>{17, 17, 17}));
    EXPECT_EQ(tiles(BlockType::WarmLamp), (std::array<int, 3>{18, 18, 18}));
    EXPECT_EQ(tiles(BlockType::OrangeLamp), (std::array<int, 3>{19, 19, 19}));
}

// Light: air lets it through, leaves dim it, every other block stops it, and only the lamps give it, each at full
// strength in its brightest channel: the lamp white, the red, green and blue lamps one channel each, the warm white
// every channel and red the most, the orange lamp red and half as much green. Mutation caught: a lamp's emission
// left at 0, a coloured lamp with a channel mixed up (or leaves as opaque as stone).
TEST(Block, LightOpacityAndEmission) {
    for (int i = 0; i < world::kBlockTypeCount; ++i) {
        const auto t = static_cast<BlockType>(i);
        const auto& info = world::blockInfo(t);
        SCOPED_TRACE(std::string(info.name));
        if (t == BlockType::Air) {
            EXPECT_EQ(info.lightOpacity, 0);
        } else if (t == BlockType::Leaves) {
            EXPECT_GT(info.lightOpacity, 0);
            EXPECT_LT(info.lightOpacity, world::kMaxLight);
        } else {
            EXPECT_EQ(info.lightOpacity, world::kMaxLight);
        }
        const bool lamp = t >= BlockType::Lamp && t <= BlockType::OrangeLamp;
        EXPECT_EQ(info.emission.brightest(), lamp ? world::kMaxLight : 0);
    }
    using world::LightColour;
    EXPECT_EQ(world::blockInfo(BlockType::Lamp).emission, (LightColour{15, 15, 15}));
    EXPECT_EQ(world::blockInfo(BlockType::RedLamp).emission, (LightColour{15, 0, 0}));
    EXPECT_EQ(world::blockInfo(BlockType::GreenLamp).emission, (LightColour{0, 15, 0}));
    EXPECT_EQ(world::blockInfo(BlockType::BlueLamp).emission, (LightColour{0, 0, 15}));
    const LightColour warm = world::blockInfo(BlockType::WarmLamp).emission,
                      orange = world::blockInfo(BlockType::OrangeLamp).emission;
    EXPECT_TRUE(warm.red == 15 && warm.green < 15 && warm.blue < warm.green && warm.blue > 0);
    EXPECT_TRUE(orange.red == 15 && orange.green >= 7 && orange.green <= 8 && orange.blue == 0);
    EXPECT_EQ(world::blockFromName("lamp"), BlockType::Lamp);
    EXPECT_EQ(world::blockFromName("red_lamp"), BlockType::RedLamp);
    EXPECT_EQ(world::blockFromName("orange_lamp"), BlockType::OrangeLamp);
}

TEST(Block, OutOfRangeValueIsSafe) {
    EXPECT_EQ(world::blockInfo(BlockType::Count).name, "air");
    EXPECT_EQ(world::blockInfo(static_cast<BlockType>(200)).name, "air");
}

} // namespace

// The one action table drives the mapper: each listed key and pad button, at its default binding, raises
// exactly its own action through the real mapper, held actions on every tick and pressed ones once.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "input/action_table.h"
#include "input/mapper.h"

namespace {

using input::Trigger;

// Which of the table's flags are set.
template <typename Table>
std::set<std::string> raised(const input::Actions& actions, const Table& table) {
    std::set<std::string> out;
    for (const auto& a : table) {
        if (a.action && actions.*a.action) out.insert(std::string(a.id));
    }
    return out;
}

TEST(ActionTable, IdsAndLabelsAreUniqueAndOnlySteeringRowsLackAFlag) {
    std::set<std::string_view> keyIds, padIds;
    for (const auto& a : input::kKeyActions) {
        EXPECT_TRUE(keyIds.insert(a.id).second) << a.id;
        EXPECT_FALSE(a.label.empty()) << a.id;
        EXPECT_EQ(a.action == nullptr, a.trigger == Trigger::Steers) << a.id;
    }
    for (const auto& a : input::kPadActions) {
        EXPECT_TRUE(padIds.insert(a.id).second) << a.id;
        EXPECT_FALSE(a.label.empty()) << a.id;
        EXPECT_EQ(a.action == nullptr, a.trigger == Trigger::Steers) << a.id;
    }
    EXPECT_EQ(keyIds.size(), 14u);
    EXPECT_EQ(padIds.size(), 13u);
}

TEST(ActionTable, EachKeyRaisesItsOwnActionHeldOrOncePerPress) {
    const input::InputConfig config;
    for (const auto& a : input::kKeyActions) {
        if (!a.action) continue;
        input::InputMapper mapper(config);
        const int key = config.keys.*a.key;
        ASSERT_GE(key, 0) << a.id << " has no default key";
        mapper.handle(input::KeyEvent{key, true});
        const input::Actions first = mapper.takeTickActions(1.0f / 60.0f);
        EXPECT_EQ(raised(first, input::kKeyActions), std::set<std::string>{std::string(a.id)}) << a.id;
        const input::Actions second = mapper.takeTickActions(1.0f / 60.0f); // still down, no new press
        EXPECT_EQ(second.*a.action, a.trigger == Trigger::Held) << a.id;
    }
}

TEST(ActionTable, EachPadButtonRaisesItsOwnActionHeldOrOncePerPress) {
    const input::InputConfig config;
    for (const auto& a : input::kPadActions) {
        if (!a.action) continue;
        input::InputMapper mapper(config);
        input::GamepadState pad;
        pad.connected = true;
        pad.buttons[static_cast<std::size_t>(config.pad.*a.button)] = true;
        mapper.setGamepadState(pad);
        const input::Actions first = mapper.takeTickActions(1.0f / 60.0f);
        EXPECT_EQ(raised(first, input::kPadActions), std::set<std::string>{std::string(a.id)}) << a.id;
        mapper.setGamepadState(pad);
        const input::Actions second = mapper.takeTickActions(1.0f / 60.0f);
        EXPECT_EQ(second.*a.action, a.trigger == Trigger::Held) << a.id;
    }
}

TEST(ActionTable, SteeringRowsMoveAndStepTheHotbar) {
    const input::InputConfig config;
    input::InputMapper mapper(config);
    mapper.handle(input::KeyEvent{config.keys.forward, true});
    mapper.handle(input::KeyEvent{config.keys.right, true});
    const input::Actions moved = mapper.takeTickActions(1.0f / 60.0f);
    EXPECT_GT(moved.move.x, 0.0f);
    EXPECT_GT(moved.move.y, 0.0f);
    input::GamepadState pad;
    pad.connected = true;
    pad.buttons[static_cast<std::size_t>(config.pad.selectNext)] = true;
    mapper.setGamepadState(pad);
    EXPECT_EQ(mapper.takeTickActions(1.0f / 60.0f).selectDelta, 1);
}

} // namespace

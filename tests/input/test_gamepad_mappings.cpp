// SDL-format gamepad mappings: good lines pass to GLFW, a malformed one is reported by its number.
#include <gtest/gtest.h>

#include "input/gamepad_mappings.h"

namespace {

// A synthetic GUID (no real pad has it), in the layout of SDL's gamecontrollerdb.txt.
constexpr const char* kGood =
    "03000000ffff0000feed000000010000,Minecrappy Test Pad,a:b0,b:b1,x:b2,y:b3,leftshoulder:b4,rightshoulder:b5,"
    "back:b6,start:b7,guide:b8,leftstick:b9,rightstick:b10,dpup:h0.1,dpdown:h0.4,dpleft:h0.8,dpright:h0.2,"
    "leftx:a0,lefty:a1,rightx:a3,righty:a4,lefttrigger:a2,righttrigger:a5,+lefty:+a1~,platform:Linux,";

TEST(GamepadMappings, GoodLinesPassCommentsAndBlanksAreSkippedBadOnesAreNumbered) {
    const std::string text =
        std::string("# a comment\n\n") + kGood + "\r\n" + "nothex00000000000000000000000000,Pad,a:b0,\n" + // line 4
        "03000000ffff0000feed000000020000,,a:b0,\n" +                                                      // line 5
        "03000000ffff0000feed000000030000,Pad,a:z9,\n" +                                                   // line 6
        "03000000ffff0000feed000000040000,Pad,wheel:b0,\n" + "03000000ffff0000feed000000050000,Pad,platform:Linux,\n" +
        "03000000ffff0000feed000000060000\n";
    const input::GamepadMappings m = input::parseGamepadMappings(text, "db.txt");
    ASSERT_EQ(m.lines.size(), 1u);
    EXPECT_EQ(m.lines[0], kGood);
    ASSERT_EQ(m.problems.size(), 6u);
    EXPECT_EQ(m.problems[0], "db.txt:4: the GUID 'nothex00000000000000000000000000' is not 32 hexadecimal digits");
    EXPECT_EQ(m.problems[1], "db.txt:5: the name is empty");
    EXPECT_EQ(m.problems[2], "db.txt:6: 'z9' for a is not bN, aN or hN.M");
    EXPECT_EQ(m.problems[3], "db.txt:7: unknown element 'wheel'");
    EXPECT_EQ(m.problems[4], "db.txt:8: the mapping maps no button or axis");
    EXPECT_EQ(m.problems[5], "db.txt:9: expected GUID,NAME,ELEMENT:SOURCE,...");
}

TEST(GamepadMappings, TheOverlaySaysWhetherThePadIsMapped) {
    EXPECT_EQ(input::padLabel(true, true, "Minecrappy Test Pad"), "Minecrappy Test Pad (mapped)");
    EXPECT_EQ(input::padLabel(true, false, "Odd Stick"), "Odd Stick (no mapping)");
    EXPECT_EQ(input::padLabel(true, false, ""), "joystick (no mapping)");
    EXPECT_EQ(input::padLabel(false, true, "Gone"), "");
}

} // namespace

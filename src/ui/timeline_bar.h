// The replay timeline's bar (session/timeline.h), drawn along the top of the window while a replay plays in it:
// buttons for the start, the previous mark, a tick back, play or pause, a tick on, the next mark and the end; the
// speed and its direction; taking over; the bar itself with the recording's marks, dragged or clicked to go to a
// tick; and a line with the tick on screen, the time of day and the state hash of what is on screen.
#pragma once
#include "session/timeline.h"

namespace ui {

// Acts on the timeline at once (a click, a drag). Between Dear ImGui's beginFrame and endFrame.
void drawTimeline(session::Timeline& timeline, const game::GameState& state);

// The keys a timeline takes in the window (input/keys.h codes): Space play or pause, Left / Right a tick back or on
// (with Shift a second), Up / Down faster or slower, R the direction, Page Up / Page Down the previous or next
// mark, Home / End the start or the end, T take over. True when the key was one of them.
bool timelineKey(session::Timeline& timeline, int key, bool shift, int tickRate);

} // namespace ui

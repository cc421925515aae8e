// Counts the fragments that pass the depth test between begin() and end() (an occlusion query,
// GL_SAMPLES_PASSED; one sample per pixel here): the fragments a frame shades and writes. Divided by
// the frame's pixels it is the overdraw, 1.0 when every pixel is shaded once; what the depth test
// rejects is not counted. --frame-stats reports it for every 30th frame (docs/ENGINE.md).
#pragma once
#include <cstdint>

#include "render/gl.h"

namespace render {

class FragmentCounter {
public:
    FragmentCounter();
    ~FragmentCounter();
    FragmentCounter(const FragmentCounter&) = delete;
    FragmentCounter& operator=(const FragmentCounter&) = delete;

    void begin();
    void end();
    // The count of the last begin()..end(); waits for those draws to finish, so read it once the frame
    // is drawn (after RenderContext::present, or submit of the frame after it) to keep the wait out of
    // the frame's own timing.
    std::uint64_t result() const;

private:
    GLuint m_query = 0;
};

} // namespace render

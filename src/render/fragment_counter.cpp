#include "render/fragment_counter.h"

namespace render {

FragmentCounter::FragmentCounter() { glGenQueries(1, &m_query); }

FragmentCounter::~FragmentCounter() { glDeleteQueries(1, &m_query); }

void FragmentCounter::begin() { glBeginQuery(GL_SAMPLES_PASSED, m_query); }

void FragmentCounter::end() { glEndQuery(GL_SAMPLES_PASSED); }

std::uint64_t FragmentCounter::result() const {
    GLuint64 n = 0;
    glGetQueryObjectui64v(m_query, GL_QUERY_RESULT, &n);
    return n;
}

} // namespace render

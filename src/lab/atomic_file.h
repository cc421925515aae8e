// Writing a result file so that the user's existing file is either replaced whole or left as it was:
// the text goes to a temporary file beside the target, and only a successful commit() renames it over
// the target. A writer that is destroyed without commit() (an exception, a refused run) removes its
// temporary file. It must never leave a half-written file under the target's name.
#pragma once
#include <filesystem>
#include <fstream>
#include <ostream>

namespace lab {

class AtomicFile {
public:
    // Opens the temporary file; throws std::runtime_error naming `target` when that is impossible.
    explicit AtomicFile(std::filesystem::path target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    std::ostream& stream() { return m_out; }
    const std::filesystem::path& target() const { return m_target; }

    // Flushes, closes and renames over the target; throws std::runtime_error naming the target when any
    // of that fails (disk full, folder removed meanwhile), after removing the temporary file.
    void commit();

private:
    std::filesystem::path m_target;
    std::filesystem::path m_temp;
    std::ofstream m_out;
    bool m_committed = false;
};

} // namespace lab

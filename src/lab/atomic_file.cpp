#include "lab/atomic_file.h"

#include <atomic>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace lab {

namespace {
std::string uniqueSuffix() {
    // Two writers in one process (or two processes) aiming at the same folder must not share a name.
    static std::atomic<unsigned> counter{0};
    std::random_device rd;
    return std::to_string(rd()) + "-" + std::to_string(counter.fetch_add(1));
}
} // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : m_target(std::move(target)) {
    if (m_target.filename().empty()) {
        throw std::runtime_error("cannot write '" + m_target.string() + "': not a file name");
    }
    m_temp = m_target;
    // Built piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    std::string tempName = ".";
    tempName += m_target.filename().string();
    tempName += ".tmp-";
    tempName += uniqueSuffix();
    m_temp.replace_filename(tempName);
    m_out.open(m_temp, std::ios::binary | std::ios::trunc);
    if (!m_out) {
        throw std::runtime_error("cannot write '" + m_target.string() + "': cannot create a file in '" +
                                 m_target.parent_path().string() + "'");
    }
}

AtomicFile::~AtomicFile() {
    if (!m_committed) {
        m_out.close();
        std::error_code ec;
        std::filesystem::remove(m_temp, ec); // best effort; a destructor must not throw
    }
}

void AtomicFile::commit() {
    m_out.flush();
    const bool written = static_cast<bool>(m_out);
    m_out.close();
    std::error_code ec;
    if (!written || m_out.fail()) {
        std::filesystem::remove(m_temp, ec);
        throw std::runtime_error("cannot write '" + m_target.string() + "': write failed (disk full?)");
    }
    std::filesystem::rename(m_temp, m_target, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(m_temp, ignored);
        throw std::runtime_error("cannot write '" + m_target.string() + "': " + ec.message());
    }
    m_committed = true;
}

} // namespace lab

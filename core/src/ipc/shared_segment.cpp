#include "archet/ipc/shared_segment.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <new>
#include <utility>

#include "archet/common/input_error.hpp"

namespace archet::ipc {

std::string random_segment_name() {
    unsigned char bytes[16];
    std::size_t got = 0;
    while (got < sizeof bytes) {
        const ssize_t n = ::getrandom(bytes + got, sizeof bytes - got, 0);
        if (n < 0 && errno != EINTR) throw std::runtime_error("getrandom failed");
        if (n > 0) got += static_cast<std::size_t>(n);
    }
    static const char* hex = "0123456789abcdef";
    std::string name = "/archet-";
    for (unsigned char b : bytes) name += hex[b >> 4], name += hex[b & 15];
    return name;
}

SharedSegment SharedSegment::create(const Layout& plan) {
    SharedSegment s;
    s.owner_ = true;
    for (int attempt = 0; attempt < 8; ++attempt) {
        s.name_ = random_segment_name();
        const int fd = ::shm_open(s.name_.c_str(), O_CREAT | O_EXCL | O_RDWR, 0600);
        if (fd < 0 && errno == EEXIST) continue;
        if (fd < 0)
            throw InputError("shared memory",
                             std::string("cannot create a segment: ") + std::strerror(errno));
        if (::ftruncate(fd, static_cast<off_t>(plan.segment_size)) != 0) {
            const int e = errno;
            ::close(fd), ::shm_unlink(s.name_.c_str());
            throw InputError("shared memory",
                             std::string("cannot size the segment: ") + std::strerror(e));
        }
        s.base_ = ::mmap(nullptr, plan.segment_size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
        ::close(fd);
        if (s.base_ == MAP_FAILED) {
            s.base_ = nullptr;
            ::shm_unlink(s.name_.c_str());
            throw InputError("shared memory",
                             std::string("cannot map the segment: ") + std::strerror(errno));
        }
        s.size_ = plan.segment_size;
        s.layout_ = plan;
        // The segment is zero-filled: construct the header and ring controls in place.
        auto* h = new (s.base_) SegmentHeader{};
        h->studio_pid = static_cast<std::int32_t>(::getpid());
        h->protocol_version = plan.protocol_version;
        h->minimum_compatible_version = plan.minimum_compatible_version;
        h->header_size = plan.header_size;
        h->segment_size = plan.segment_size;
        h->commands = plan.commands, h->probes = plan.probes, h->shapes = plan.shapes,
        h->status = plan.status;
        for (const RingDescriptor* d : {&h->commands, &h->probes, &h->shapes, &h->status})
            new (static_cast<char*>(s.base_) + d->offset) RingControl{};
        // Last: a reader (an engine, reclaim_stale_segments) judges a header by its magic.
        std::atomic_thread_fence(std::memory_order_release);
        h->magic = plan.magic;
        return s;
    }
    throw InputError("shared memory", "could not find a free segment name");
}

SharedSegment SharedSegment::attach(const std::string& name) {
    const std::string where = "segment " + name;
    if (name.size() < 2 || name[0] != '/' || name.find('/', 1) != std::string::npos)
        throw InputError(where, "a segment name starts with / and has no other /");
    const int fd = ::shm_open(name.c_str(), O_RDWR, 0);
    if (fd < 0) throw InputError(where, std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
        ::close(fd);
        throw InputError(where, "cannot stat");
    }
    if (st.st_uid != ::geteuid() || (st.st_mode & 077) != 0) {
        ::close(fd);
        throw InputError(where, "belongs to another user or is open to others (must be mode 0600)");
    }
    const auto size = static_cast<std::uint64_t>(st.st_size);
    if (size < sizeof(SegmentHeader)) {
        ::close(fd);
        throw InputError(where, "too small to hold a header");
    }
    SharedSegment s;
    s.base_ = ::mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    ::close(fd);
    if (s.base_ == MAP_FAILED) {
        s.base_ = nullptr;
        throw InputError(where, std::string("cannot map: ") + std::strerror(errno));
    }
    s.name_ = name;
    s.size_ = size;
    // Copy the plain fields out before judging them: the other side may still be writing.
    s.layout_ = read_layout(s.header());
    if (const char* problem = validate_layout(s.layout_, size)) throw InputError(where, problem);
    return s;
}

bool process_gone(std::int32_t pid) {
    return pid <= 0 || (::kill(pid, 0) != 0 && errno == ESRCH);
}

namespace {

bool is_segment_name(const std::string& name) {
    const std::string prefix = "archet-";
    if (name.size() != prefix.size() + 32 || name.compare(0, prefix.size(), prefix) != 0)
        return false;
    for (std::size_t i = prefix.size(); i < name.size(); ++i)
        if (!std::isxdigit(static_cast<unsigned char>(name[i])) ||
            std::isupper(static_cast<unsigned char>(name[i])))
            return false;
    return true;
}

// Whether the segment `name` (with its leading /) is one of ours whose two processes died.
bool stale(const std::string& name) {
    const int fd = ::shm_open(name.c_str(), O_RDONLY | O_NOFOLLOW, 0);
    if (fd < 0) return false;
    struct stat st {};
    bool dead = false;
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_uid == ::geteuid() &&
        (st.st_mode & 0777) == 0600 &&
        static_cast<std::uint64_t>(st.st_size) >= sizeof(SegmentHeader)) {
        const auto size = static_cast<std::uint64_t>(st.st_size);
        void* base = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
        if (base != MAP_FAILED) {
            const auto& header = *static_cast<const SegmentHeader*>(base);
            if (validate_layout(read_layout(header), size) == nullptr)
                dead = header.studio_pid > 0 && process_gone(header.studio_pid) &&
                       process_gone(header.engine_pid.load());
            ::munmap(base, size);
        }
    }
    ::close(fd);
    return dead;
}

}  // namespace

std::vector<std::string> reclaim_stale_segments(const std::string& folder) {
    std::vector<std::string> removed;
    DIR* dir = ::opendir(folder.c_str());
    if (!dir) return removed;
    while (const dirent* entry = ::readdir(dir)) {
        const std::string name = entry->d_name;
        if (!is_segment_name(name)) continue;
        if (stale("/" + name) && ::shm_unlink(("/" + name).c_str()) == 0)
            removed.push_back("/" + name);
    }
    ::closedir(dir);
    return removed;
}

SharedSegment::SharedSegment(SharedSegment&& o) noexcept
    : name_(std::move(o.name_)),
      base_(std::exchange(o.base_, nullptr)),
      size_(o.size_),
      owner_(std::exchange(o.owner_, false)),
      layout_(o.layout_) {}

SharedSegment& SharedSegment::operator=(SharedSegment&& o) noexcept {
    if (this != &o) {
        this->~SharedSegment();
        new (this) SharedSegment(std::move(o));
    }
    return *this;
}

void SharedSegment::unlink() {
    if (!name_.empty()) ::shm_unlink(name_.c_str());
    owner_ = false;
}

SharedSegment::~SharedSegment() {
    if (base_) ::munmap(base_, size_);
    if (owner_) ::shm_unlink(name_.c_str());
}

}  // namespace archet::ipc

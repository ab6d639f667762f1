#include "keyrot/output.hpp"

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "keyrot/error.hpp"

namespace keyrot {

void write_file_atomically(const std::string& path, std::string_view data) {
    const auto fail = [&path](int err) {
        return error(fmt::format("cannot write '{}': {}", path, std::strerror(err)));
    };
    const std::filesystem::path target(path);
    std::string temp = (target.parent_path() / fmt::format(".{}.keyrot-XXXXXX", target.filename().string())).string();
    const int fd = ::mkstemp(temp.data());
    if (fd < 0) throw fail(errno);
    const char* p = data.data();
    std::size_t left = data.size();
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            std::remove(temp.c_str());
            throw fail(err);
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
    // mkstemp creates the file 0600; give it the usual permissions.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    ::fchmod(fd, 0666 & ~mask);
    if (::close(fd) != 0 || std::rename(temp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        std::remove(temp.c_str());
        throw fail(err);
    }
}

}  // namespace keyrot

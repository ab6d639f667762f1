// SPDX-License-Identifier: MIT
#pragma once
// The inputs of a command: files, a file on standard input, or anything
// that can be read only once (a pipe, a FIFO, a device) copied to a
// temporary file (unlinked at once) as it is first read, so that an input can
// be read twice (validated first, then streamed) in constant memory.
#include <sys/types.h>

#include <ctime>
#include <istream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "io/common/format.hpp"

namespace keyrot {

/// The name of standard input and standard output on the command line.
inline constexpr std::string_view standard_stream = "-";
inline bool is_standard_stream(std::string_view name) noexcept { return name == standard_stream; }
/// How messages name the input `name`: the path, or "<stdin>" for "-".
inline std::string source_name(const std::string& name) { return is_standard_stream(name) ? "<stdin>" : name; }

/// The message for an input that changed while keyrot read it.
std::string changed_while_read(const std::string& source);

class input_source {
public:
    /// `name` is a path or "-" (standard input, read from `stdin_stream`; in
    /// place when that is std::cin and the process's standard input a file).
    /// Throws keyrot::error ("cannot read 'x.csv': No such file or directory").
    input_source(const std::string& name, std::istream& stdin_stream);
    input_source(const input_source&) = delete;
    input_source& operator=(const input_source&) = delete;
    ~input_source();

    struct spool;  // how an input that can be read only once is read again

    const std::string& source() const noexcept { return source_; }  ///< for messages: the path or "<stdin>"
    /// A fresh stream from the start (each has its own position).
    std::unique_ptr<std::istream> open() const;
    /// `given` (--from), else by the name's extension, else sniffed from the content.
    format detect(std::optional<format> given) const;
    /// Whether the input is the file standard output writes (keyrot
    /// resample a.csv >> a.csv).
    bool is_standard_output() const;

private:
    std::string name_, source_;
    int fd_ = -1;        // the file, or the spool's copy
    int input_fd_ = -1;  // a named input that is spooled (a FIFO)
    std::unique_ptr<spool> spool_;
    off_t start_ = 0;  // where the input begins in fd_
    // The file as the first open() found it (size, modification time).
    mutable bool opened_ = false;
    mutable off_t size_ = 0;
    mutable std::timespec modified_{};
};

}  // namespace keyrot

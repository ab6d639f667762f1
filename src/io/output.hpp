#pragma once
// Writing results so that a failure never leaves a partial file behind.
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>

namespace keyrot {

/// Whether output to `path` goes to a temporary file renamed into place (a
/// regular file, or none yet) rather than straight into `path` (a device, a
/// pipe, or a descriptor: /dev/null, /dev/stdout, /dev/fd/3, a FIFO), where
/// it cannot be taken back.
bool replaced_on_commit(const std::string& path);

/// Writes `text` to `out` (standard output) and flushes it. Throws
/// keyrot::error with the reason ("cannot write to standard output: No
/// space left on device") when it cannot.
void write_to_stream(std::ostream& out, std::string_view text);

/// A temporary file beside `path` (beside the file it links to, for a
/// symbolic link of the caller's or of the directory's owner), written in
/// pieces and renamed into place by commit(), durably (fsync of the file,
/// then of its directory), so `path` is either untouched or complete; the
/// file keeps the permission bits of the one it replaces (not set-user-ID
/// or set-group-ID), and a file the caller may not write is refused.
/// Destroyed without commit(), or on SIGINT, SIGTERM or SIGHUP, it removes
/// the temporary file. A device, a pipe or a descriptor (/dev/stdout) is
/// written straight into instead. Throws keyrot::error ("cannot write
/// 'out.csv': Permission denied") on failure.
class output_file {
public:
    explicit output_file(std::string path);
    output_file(const output_file&) = delete;
    output_file& operator=(const output_file&) = delete;
    ~output_file();
    void write(std::string_view data);
    void commit();

private:
    [[noreturn]] void fail(int err) const;
    /// The file `path` names through symbolic links (which may not exist yet).
    std::string resolve(const std::string& path) const;

    std::string path_, target_, temp_;  // no temp_: straight into path_
    int fd_ = -1;
    long long written_ = 0;
    std::optional<std::size_t> slot_;  // temp_'s, for the signal handler
};

/// output_file(path), write(data), commit().
void write_file_atomically(const std::string& path, std::string_view data);

}  // namespace keyrot

// SPDX-License-Identifier: MIT
#pragma once
// Writing results so that a failure never leaves a partial file behind.
#include <cstddef>
#include <iosfwd>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace keyrot {

class durable_batch;

/// How an output file is put in place. By default: written beside its
/// target and put in its place at once (a file there exchanged with it,
/// then removed; else renamed), so that readers never see a partial file
/// and a failure leaves the old one, but not waited for on the disk. With
/// `fsync` (--fsync), also durable against a power cut: the new file's data
/// on disk before it is put in place, that change on disk before success;
/// with a `batch` as well, that wait is paid once for the batch's files
/// (durable_batch) rather than once for each.
struct commit_mode {
    bool fsync = false;
    durable_batch* batch = nullptr;
    /// -o PATH through a symbolic link replaces the file it names (as
    /// output_file says); --output-dir replaces whatever sits at the name
    /// (a link is renamed over, never written through).
    bool follow_links = true;
};

/// Whether output to `path` goes to a temporary file renamed into place (a
/// regular file, or none yet) rather than straight into `path` (a device, a
/// pipe, or a descriptor: /dev/null, /dev/stdout, /dev/fd/3, a FIFO), where
/// it cannot be taken back.
bool replaced_on_commit(const std::string& path);

/// Standard output redirected to a regular file (keyrot ... > out.csv):
/// what is written there after the mark can be taken back, by cutting the
/// file back to it, so that one pass may write there as into a temporary
/// file. Only where that harms nobody: standard output at the end of its
/// file and not appending (after `>>` another process may append too), the
/// file one that may be cut (not append-only) and not standard error's
/// (`2>&1`: the warnings, held back in one pass, would move). A pipe, a
/// terminal or a device cannot take anything back.
class standard_output_mark {
public:
    /// None unless `out` is std::cout on such a file.
    static std::optional<standard_output_mark> of(std::ostream& out);
    /// Cuts the file back to the mark, dropping what the stream still
    /// holds; throws keyrot::error if it cannot.
    void take_back(std::ostream& out) const;

private:
    explicit standard_output_mark(long long at) : at_(at) {}
    long long at_;
};

/// Writes `text` to `out` (standard output) and flushes it. Throws
/// keyrot::error with the reason ("cannot write to standard output: No
/// space left on device") when it cannot.
void write_to_stream(std::ostream& out, std::string_view text);

/// A temporary file beside `path` (beside the file it links to, for a
/// symbolic link of the caller's or of the directory's owner, unless
/// `mode` follows no link), written in pieces and renamed into place by
/// commit() as `mode` says (or handed to its batch, which renames it), so
/// `path` is either untouched or complete; the file keeps the permission
/// bits of the one it replaces (not set-user-ID or set-group-ID), and, when
/// root replaces it, its owner and group, as `sed -i` does; a file the
/// caller may not write is refused.
/// Destroyed without commit(), or on SIGINT, SIGTERM or SIGHUP, it removes
/// the temporary file. A device, a pipe or a descriptor (/dev/stdout) is
/// written straight into instead. Throws keyrot::error ("cannot write
/// 'out.csv': Permission denied") on failure.
class output_file {
public:
    explicit output_file(std::string path, commit_mode mode = {});
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
    commit_mode mode_;
    int fd_ = -1;
    long long written_ = 0;
    std::optional<std::size_t> slot_;  // temp_'s, for the signal handler
};

/// output_file(path, mode), write(data), commit().
void write_file_atomically(const std::string& path, std::string_view data, commit_mode mode = {});

/// The files of a batch (--output-dir with --fsync), made durable
/// together: each written and closed, then one sync of the filesystems
/// they are on (syncfs), then each renamed into place, then one more sync
/// for the renames. A power cut leaves every target either as it was or
/// complete, and the disk is waited for twice in all, not twice a file.
/// What is not put in place by finish() (a failure, an exception) is
/// removed with the batch. Files may be added from several threads.
class durable_batch {
public:
    durable_batch() = default;
    durable_batch(const durable_batch&) = delete;
    durable_batch& operator=(const durable_batch&) = delete;
    ~durable_batch();
    /// Syncs and renames every file added. Throws keyrot::error naming the
    /// first file it could not put in place (the rest are put in place).
    void finish();

private:
    friend class output_file;
    struct pending {
        std::string path, temp, target;
        std::optional<std::size_t> slot;
    };
    void add(pending file);

    std::mutex mutex_;
    std::vector<pending> files_;
};

}  // namespace keyrot

#pragma once
// Writing results so that a failure never leaves a partial file behind.
#include <string>
#include <string_view>

namespace keyrot {

/// Whether output to `path` goes to a temporary file renamed into place (a
/// regular file, or none yet) rather than straight into `path` (a device or
/// a pipe: /dev/null, /dev/stdout, a FIFO), where it cannot be taken back.
bool replaced_on_commit(const std::string& path);

/// A temporary file beside `path` (beside the file it links to, for a
/// symbolic link), written in pieces and renamed into place by commit(), so
/// `path` is either untouched or complete; the file keeps the mode of the
/// one it replaces. Destroyed without commit(), it removes the temporary
/// file. A device or a pipe is written straight into instead. Throws
/// keyrot::error ("cannot write 'out.csv': Permission denied") on failure.
class output_file {
public:
    explicit output_file(std::string path);
    output_file(const output_file&) = delete;
    output_file& operator=(const output_file&) = delete;
    ~output_file();
    void write(std::string_view data);
    void commit();

private:
    [[noreturn]] void fail(int err);

    std::string path_, target_, temp_;  // no temp_: straight into path_
    int fd_ = -1;
    long long written_ = 0;
};

/// output_file(path), write(data), commit().
void write_file_atomically(const std::string& path, std::string_view data);

}  // namespace keyrot

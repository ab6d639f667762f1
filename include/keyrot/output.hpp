#pragma once
// Writing results so that a failure never leaves a partial file behind.
#include <string>
#include <string_view>

namespace keyrot {

/// A temporary file beside `path`, written in pieces and renamed into place
/// by commit(), so `path` is either untouched or complete. Destroyed without
/// commit(), it removes the temporary file. Throws keyrot::error
/// ("cannot write 'out.csv': Permission denied") on failure.
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

    std::string path_, temp_;
    int fd_ = -1;
    long long written_ = 0;
};

/// output_file(path), write(data), commit().
void write_file_atomically(const std::string& path, std::string_view data);

}  // namespace keyrot

// SPDX-License-Identifier: MIT
#pragma once
// Bytes read into memory whole (a .glb file).
#include <cstddef>
#include <cstdlib>
#include <istream>
#include <memory>
#include <string_view>

namespace keyrot {

/// A file's bytes read into memory at once: not zeroed before they are
/// read into, and, from 2 MiB, in the kernel's huge pages where it gives
/// them. (Read into ordinary pages, a large file costs more in page faults,
/// one each 4 KiB, than in reading.)
class byte_block {
public:
    /// Reads up to `n` bytes more from `in`; false where none came.
    bool read(std::istream& in, std::size_t n);
    std::string_view view() const noexcept { return {data_.get(), size_}; }
    std::size_t size() const noexcept { return size_; }

private:
    void reserve(std::size_t n);  // room for n bytes in all
    struct release {
        void operator()(char* p) const noexcept { std::free(p); }
    };
    std::unique_ptr<char[], release> data_;
    std::size_t size_ = 0, capacity_ = 0;
};

}  // namespace keyrot

// SPDX-License-Identifier: MIT
#include "io/common/byte_block.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cstring>
#include <new>

namespace keyrot {

bool byte_block::read(std::istream& in, std::size_t n) {
    if (capacity_ - size_ < n) reserve(std::max(size_ + n, 2 * capacity_));
    in.read(data_.get() + size_, static_cast<std::streamsize>(n));
    const auto got = static_cast<std::size_t>(in.gcount());
    size_ += got;
    return got > 0;
}

void byte_block::reserve(std::size_t n) {
    constexpr std::size_t huge_page = std::size_t{2} << 20, small = alignof(std::max_align_t);
    const std::size_t align = n >= huge_page ? huge_page : small;
    const std::size_t capacity = (n + align - 1) / align * align;
    std::unique_ptr<char[], release> more(static_cast<char*>(std::aligned_alloc(align, capacity)));
    if (!more) throw std::bad_alloc();
    // Advice only: where the kernel gives no huge pages the block is as good.
    if (align == huge_page) ::madvise(more.get(), capacity, MADV_HUGEPAGE);
    if (size_ > 0) std::memcpy(more.get(), data_.get(), size_);
    data_ = std::move(more);
    capacity_ = capacity;
}

}  // namespace keyrot

// SPDX-License-Identifier: MIT
#include "ground/warnings.hpp"

#include "keyrot/error.hpp"

namespace keyrot {

void print_error(std::ostream& err, std::string_view message) { err << "keyrot: " << printable(message) << '\n'; }

void warnings::once(const std::string& kind, const std::string& message) {
    const std::lock_guard lock(mutex_);
    if (said_.insert(kind).second) print_error(err_, "warning: " + source_ + ": " + message);
}

void warnings::adopt(warnings& other, std::string_view printed) {
    const std::scoped_lock lock(mutex_, other.mutex_);
    err_ << printed;
    said_.insert(other.said_.begin(), other.said_.end());
}

}  // namespace keyrot

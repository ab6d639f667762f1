#include "keyrot/error.hpp"

namespace keyrot {

void warnings::once(const std::string& kind, const std::string& message) {
    if (said_.insert(kind).second) err_ << "keyrot: warning: " << source_ << ": " << message << '\n';
}

}  // namespace keyrot

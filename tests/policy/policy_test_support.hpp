// What the policy-table tests share: the decoder's error message for a byte string (empty when
// the table decodes).
#pragma once

#include <string>

#include "policy/policy_table.hpp"

namespace ecorail::policy::testing {

inline std::string decode_error_of(const std::string& bytes) {
  try {
    decode_policy(bytes, "t.bin");
  } catch (const PolicyFormatError& e) {
    return e.what();
  }
  return "";
}

}  // namespace ecorail::policy::testing

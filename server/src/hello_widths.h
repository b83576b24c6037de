#pragma once
// Protobuf reads a varint into a 32-bit field by keeping its low 32 bits, so a Hello
// whose view.byte_budget is 2^63 arrives as 0 ("no budget"), and a seat of 2^32 + 1
// as seat 1. The Hello's 32-bit fields are therefore checked on the raw bytes,
// before that narrowing: each must fit its type (the enums an int32). Socket-free.
#include <optional>
#include <string>
#include <string_view>

#include "server/server.h"
#include "wire.pb.h"

namespace server {

struct WideField {
  physics::wire::ErrorCode code = physics::wire::ERROR_MALFORMED;
  std::string text;  // names the field and the value sent
  DropReason reason = DropReason::Malformed;
};

// `frame`: a ClientMessage's bytes (that already parsed). The first 32-bit field of
// its Hello whose value on the wire does not fit, or nullopt.
std::optional<WideField> find_wide_hello_field(std::string_view frame);

}  // namespace server

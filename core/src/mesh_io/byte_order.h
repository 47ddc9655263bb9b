// SPDX-License-Identifier: AGPL-3.0-or-later
// Binary mesh files are little endian (PLY as dot writes it, STL): values
// are written in that order whatever the host's.
#ifndef DOT_CORE_MESH_IO_BYTE_ORDER_H_
#define DOT_CORE_MESH_IO_BYTE_ORDER_H_

#include <algorithm>
#include <cstring>
#include <ostream>

namespace dot {

inline constexpr bool kLittleEndianHost =
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

template <typename T>
void PutLittleEndian(std::ostream& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (!kLittleEndianHost) std::reverse(bytes, bytes + sizeof(T));
  out.write(bytes, sizeof(T));
}

}  // namespace dot

#endif  // DOT_CORE_MESH_IO_BYTE_ORDER_H_

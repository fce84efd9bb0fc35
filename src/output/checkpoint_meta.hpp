#pragma once
// Internals of checkpoint.cpp: the checksum and the HDF5 attributes holding it and the model's
// fingerprint.
#include <hdf5.h>

#include <cstdint>
#include <optional>
#include <string>

#include "emcontact/output/checkpoint.hpp"

namespace emc::output::detail {

/// FNV-1a 64 over the stored scalars, arrays (with their lengths) and the model fingerprint.
std::uint64_t checksum(const Checkpoint& c);
/// Its parts, for a sum over blocks held by several ranks (checkpoint_parallel.cpp): the sum of
/// the scalars, then for each of u, V, last_increment its length (fnv_length) and its values in
/// order (fnv_bytes), then checksum_tail (the active set, its states and the model).
std::uint64_t checksum_head(const Checkpoint& c);
void fnv_bytes(std::uint64_t& h, const void* data, std::size_t bytes);
void fnv_length(std::uint64_t& h, std::uint64_t n);
void checksum_tail(std::uint64_t& h, const Checkpoint& c);

/// Values [first, first + count) of u, V and last_increment.
struct Slice {
  unsigned long long first = 0, count = 0;
};
/// The checkpoint at `path` with only `slice` of u, V and last_increment (each dataset's length
/// checked against `shape` as by read_checkpoint; a last_increment of none stays empty), the
/// stored checksum in `sum`, not compared; `increment`: whether last_increment has values.
Checkpoint read_block(const std::string& path, const CheckpointShape& shape, const Slice& slice,
                      std::uint64_t& sum, bool& increment);

void write_string_attribute(hid_t file, const char* name, const std::string& s,
                            const std::string& path);
void write_u64_attribute(hid_t file, const char* name, std::uint64_t v, const std::string& path);
/// nullopt if the file has no such attribute; throws emc::Error if it cannot be read.
std::optional<std::string> read_string_attribute(hid_t file, const char* name,
                                                 const std::string& path);
std::optional<std::uint64_t> read_u64_attribute(hid_t file, const char* name,
                                                const std::string& path);

}  // namespace emc::output::detail

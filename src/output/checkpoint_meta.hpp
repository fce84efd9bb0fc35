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

void write_string_attribute(hid_t file, const char* name, const std::string& s,
                            const std::string& path);
void write_u64_attribute(hid_t file, const char* name, std::uint64_t v, const std::string& path);
/// nullopt if the file has no such attribute; throws emc::Error if it cannot be read.
std::optional<std::string> read_string_attribute(hid_t file, const char* name,
                                                 const std::string& path);
std::optional<std::uint64_t> read_u64_attribute(hid_t file, const char* name,
                                                const std::string& path);

}  // namespace emc::output::detail

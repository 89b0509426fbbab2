#pragma once
/// @brief Reproducible .vdb files: the header's file id derived from the content.

#include <filesystem>

namespace ligsim {

/// OpenVDB writes a random UUID into the header of every .vdb file, so two writes of the same
/// grid differ in 36 bytes. This replaces it, in place, with one derived from the rest of the
/// file: the same grid gives the same bytes, and the build cache, which keys a stage on its
/// upstream outputs' bytes, still trusts the stages downstream of a rerun that changed nothing.
/// Throws InputError if `vdb_file` has no OpenVDB header with a text UUID.
void make_vdb_file_id_reproducible(const std::filesystem::path& vdb_file);

} // namespace ligsim

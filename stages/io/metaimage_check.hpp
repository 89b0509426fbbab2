#pragma once
/// @brief Checks a MetaImage header (.mha, .mhd) before ITK's MetaIO reads it: ITK 5.2 reads
/// `NDims = -3` as a huge count and loops over the file for as long as it takes.

#include <filesystem>

namespace ligsim::io {

/// Throws InputError naming the file and line unless the header's `NDims` (the lines
/// `Key = Value` up to `ElementDataFile`) is a whole number from 1 to 10, as MetaIO allows.
/// Other fields are left to MetaIO, which reads them within that count.
void check_metaimage_header(const std::filesystem::path& file);

} // namespace ligsim::io

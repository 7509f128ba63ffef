// Multi-view outputs compared view by view. A multi-view render is either a directory of
// per-view images (matched with the reference's directory by file name) or a quilt: one atlas
// of cols × rows equally sized views, view 0 at the bottom-left, then left to right and bottom
// to top (the Looking Glass convention, DESIGN.md "Display profiles"), its layout named in the
// file name as NAME_qs{cols}x{rows}a{aspect}.png.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "metrics/errors.h"
#include "metrics/image.h"

namespace ddish::metrics {

struct QuiltLayout {
  int cols = 1;
  int rows = 1;
  int views() const { return cols * rows; }
};

// The layout named by "_qs{cols}x{rows}" in a file name (the aspect part is not needed to split
// an atlas), or nothing when the name has none.
std::optional<QuiltLayout> quilt_layout_from_name(const std::string& filename);

// Parses "COLSxROWS" (e.g. "8x6"); throws std::invalid_argument otherwise.
QuiltLayout parse_quilt_layout(const std::string& text);

// Splits a quilt into its first `views` views (all cells when views <= 0), view 0 first.
// Throws std::invalid_argument when the atlas does not divide into the layout or views exceeds
// the cells.
std::vector<Image> split_quilt(const Image& quilt, const QuiltLayout& layout, int views = 0);

struct ViewErrors {
  std::string name;  // file name, or "view N" for quilt cells
  ImageErrors errors;
};

// Compares every image file of `dir` with the file of the same name in `reference_dir`, in
// file-name order. Files that are not images (by extension) are skipped. Throws
// std::invalid_argument when a name is missing on either side, when no image is found, or when
// a pair differs in size (naming the file).
std::vector<ViewErrors> compare_directories(const std::filesystem::path& dir,
                                            const std::filesystem::path& reference_dir);

// Compares two quilts view by view.
std::vector<ViewErrors> compare_quilts(const Image& quilt, const Image& reference,
                                       const QuiltLayout& layout, int views = 0);

// The mean of each figure over views (PSNR is averaged in dB, +inf if any view is identical).
ImageErrors mean_errors(const std::vector<ViewErrors>& views);

}  // namespace ddish::metrics

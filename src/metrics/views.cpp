#include "metrics/views.h"

#include <algorithm>
#include <cctype>
#include <regex>
#include <set>
#include <stdexcept>

#include "metrics/image_io.h"

namespace ddish::metrics {

std::optional<QuiltLayout> quilt_layout_from_name(const std::string& filename) {
  static const std::regex re(R"(_qs(\d+)x(\d+))");
  std::smatch m;
  if (!std::regex_search(filename, m, re)) return std::nullopt;
  QuiltLayout q{std::stoi(m[1].str()), std::stoi(m[2].str())};
  if (q.cols < 1 || q.rows < 1) return std::nullopt;
  return q;
}

QuiltLayout parse_quilt_layout(const std::string& text) {
  static const std::regex re(R"((\d{1,4})x(\d{1,4}))");
  std::smatch m;
  if (std::regex_match(text, m, re)) {
    QuiltLayout q{std::stoi(m[1].str()), std::stoi(m[2].str())};
    if (q.cols >= 1 && q.rows >= 1) return q;
  }
  throw std::invalid_argument("quilt layout '" + text + "' is not COLSxROWS (e.g. 8x6)");
}

std::vector<Image> split_quilt(const Image& quilt, const QuiltLayout& layout, int views) {
  if (layout.cols < 1 || layout.rows < 1 || quilt.width() % layout.cols != 0 ||
      quilt.height() % layout.rows != 0)
    throw std::invalid_argument(
        "a " + std::to_string(quilt.width()) + "x" + std::to_string(quilt.height()) +
        " image does not divide into " + std::to_string(layout.cols) + "x" +
        std::to_string(layout.rows) + " quilt views");
  if (views <= 0) views = layout.views();
  if (views > layout.views())
    throw std::invalid_argument(std::to_string(views) + " views do not fit a " +
                                std::to_string(layout.cols) + "x" + std::to_string(layout.rows) +
                                " quilt");
  const int vw = quilt.width() / layout.cols;
  const int vh = quilt.height() / layout.rows;
  std::vector<Image> out;
  for (int i = 0; i < views; ++i) {
    int col = i % layout.cols;
    int row_from_bottom = i / layout.cols;  // view 0 is at the bottom-left
    out.push_back(quilt.crop(col * vw, (layout.rows - 1 - row_from_bottom) * vh, vw, vh));
  }
  return out;
}

namespace {

bool is_image_file(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::set<std::string> known{".exr", ".png", ".jpg", ".jpeg", ".tif",
                                           ".tiff", ".hdr", ".pfm", ".ppm", ".bmp"};
  return known.count(ext) > 0;
}

std::set<std::string> image_names(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file() && is_image_file(entry.path()))
      names.insert(entry.path().filename().string());
  return names;
}

}  // namespace

std::vector<ViewErrors> compare_directories(const std::filesystem::path& dir,
                                            const std::filesystem::path& reference_dir) {
  const std::set<std::string> a = image_names(dir);
  const std::set<std::string> b = image_names(reference_dir);
  for (const std::string& n : a)
    if (!b.count(n))
      throw std::invalid_argument(n + " has no match in " + reference_dir.string());
  for (const std::string& n : b)
    if (!a.count(n)) throw std::invalid_argument(n + " is missing from " + dir.string());
  if (a.empty()) throw std::invalid_argument("no images in " + dir.string());

  std::vector<ViewErrors> out;
  for (const std::string& n : a) {  // std::set iterates in file-name order
    Image image = read_image(dir / n);
    Image reference = read_image(reference_dir / n);
    try {
      out.push_back({n, compute_errors(image, reference)});
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(n + ": " + e.what());
    }
  }
  return out;
}

std::vector<ViewErrors> compare_quilts(const Image& quilt, const Image& reference,
                                       const QuiltLayout& layout, int views) {
  require_same_size(quilt, reference);
  std::vector<Image> a = split_quilt(quilt, layout, views);
  std::vector<Image> b = split_quilt(reference, layout, views);
  std::vector<ViewErrors> out;
  for (std::size_t i = 0; i < a.size(); ++i)
    out.push_back({"view " + std::to_string(i), compute_errors(a[i], b[i])});
  return out;
}

ImageErrors mean_errors(const std::vector<ViewErrors>& views) {
  ImageErrors m;
  if (views.empty()) return m;
  for (const ViewErrors& v : views) {
    m.psnr += v.errors.psnr;
    m.ssim += v.errors.ssim;
    m.rmse += v.errors.rmse;
    m.relmse += v.errors.relmse;
  }
  double n = static_cast<double>(views.size());
  m.psnr /= n;
  m.ssim /= n;
  m.rmse /= n;
  m.relmse /= n;
  return m;
}

}  // namespace ddish::metrics

// ddish compare IMAGE REFERENCE [--json] [--quilt COLSxROWS] [--views N]
//
// Error figures of an image against its reference (src/metrics/): PSNR and SSIM on display
// values, RMSE and relative MSE on linear values. IMAGE and REFERENCE are two image files, or
// two directories of per-view images matched by file name, or two quilts compared view by view
// (--quilt, or --views with the layout taken from the NAME_qs{cols}x{rows} file name).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "metrics/errors.h"
#include "metrics/image_io.h"
#include "metrics/views.h"

namespace ddish::app {
namespace {

namespace fs = std::filesystem;
using metrics::format_figure;

struct CompareArgs {
  std::string image;
  std::string reference;
  bool json = false;
  std::string quilt;  // "COLSxROWS"
  int views = 0;
};

void print_single(const metrics::ImageErrors& e) {
  std::printf("psnr    %s dB\n", format_figure(e.psnr).c_str());
  std::printf("ssim    %s\n", format_figure(e.ssim).c_str());
  std::printf("rmse    %s\n", format_figure(e.rmse).c_str());
  std::printf("relmse  %s\n", format_figure(e.relmse).c_str());
}

void print_table(const std::vector<metrics::ViewErrors>& views) {
  std::size_t width = 4;
  for (const auto& v : views) width = std::max(width, v.name.size());
  auto row = [&](const std::string& name, const std::string& a, const std::string& b,
                 const std::string& c, const std::string& d) {
    std::printf("%s\n", fmt::format("{:<{}}  {:>10}  {:>10}  {:>12}  {:>12}", name, width, a, b,
                                    c, d)
                            .c_str());
  };
  row("view", "psnr (dB)", "ssim", "rmse", "relmse");
  auto figures = [&](const std::string& name, const metrics::ImageErrors& e) {
    row(name, format_figure(e.psnr), format_figure(e.ssim), format_figure(e.rmse),
        format_figure(e.relmse));
  };
  for (const auto& v : views) figures(v.name, v.errors);
  figures("mean", metrics::mean_errors(views));
}

int run_compare(const CompareArgs& args) {
  const fs::path image_path(args.image);
  const fs::path reference_path(args.reference);
  const bool image_dir = fs::is_directory(image_path);
  const bool reference_dir = fs::is_directory(reference_path);
  if (image_dir != reference_dir)
    throw std::invalid_argument("compare a file with a file or a directory with a directory (" +
                                args.image + ", " + args.reference + ")");

  nlohmann::ordered_json doc;
  doc["image"] = args.image;
  doc["reference"] = args.reference;

  std::vector<metrics::ViewErrors> views;
  bool per_view = image_dir;
  if (image_dir) {
    if (!args.quilt.empty() || args.views > 0)
      throw std::invalid_argument("--quilt and --views split quilt files, not directories");
    views = metrics::compare_directories(image_path, reference_path);
  } else {
    metrics::Image image = metrics::read_image(image_path);
    metrics::Image reference = metrics::read_image(reference_path);
    if (!args.quilt.empty() || args.views > 0) {
      per_view = true;
      std::optional<metrics::QuiltLayout> layout;
      if (!args.quilt.empty())
        layout = metrics::parse_quilt_layout(args.quilt);
      else
        layout = metrics::quilt_layout_from_name(image_path.filename().string());
      if (!layout)
        throw std::invalid_argument(image_path.filename().string() +
                                    " names no quilt layout (_qsCOLSxROWS); give --quilt");
      views = metrics::compare_quilts(image, reference, *layout, args.views);
    } else {
      metrics::ImageErrors e = metrics::compute_errors(image, reference);
      if (args.json) {
        doc.update(metrics::to_json(e));
        std::printf("%s\n", doc.dump(2).c_str());
      } else {
        print_single(e);
      }
      return 0;
    }
  }

  if (per_view) {
    if (args.json) {
      nlohmann::ordered_json list = nlohmann::ordered_json::array();
      for (const auto& v : views) {
        nlohmann::ordered_json j;
        j["name"] = v.name;
        j.update(metrics::to_json(v.errors));
        list.push_back(j);
      }
      doc["views"] = list;
      doc["mean"] = metrics::to_json(metrics::mean_errors(views));
      std::printf("%s\n", doc.dump(2).c_str());
    } else {
      print_table(views);
    }
  }
  return 0;
}

Action add_compare(CLI::App& root) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = root.add_subcommand(
      "compare",
      "error of IMAGE against REFERENCE (the reference comes second): PSNR and SSIM on display "
      "values (linear values clamped to [0, 1] and sRGB-encoded), RMSE and relative MSE on "
      "linear values");
  cmd->add_option("image", args->image,
                  "the image to judge: a file, or a directory of per-view images")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("reference", args->reference, 
                  "the reference (ground truth), second: a file, or a directory with the same "
                  "names")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_flag("--json", args->json, "write the figures as JSON on stdout");
  cmd->add_option("--quilt", args->quilt,
                  "compare two quilts view by view with this layout, COLSxROWS (view 0 at the "
                  "bottom-left)");
  cmd->add_option("--views", args->views,
                  "compare the first N views of two quilts (layout from --quilt or the "
                  "_qsCOLSxROWS file name)")
      ->check(CLI::PositiveNumber);
  return [args] { return run_compare(*args); };
}

}  // namespace

DDISH_COMMAND(50, add_compare);

}  // namespace ddish::app

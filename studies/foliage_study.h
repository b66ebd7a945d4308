// The speed/accuracy trade of the Luft, Balzer & Deussen (2007) preprocessing, measured by
// the program itself (DESIGN.md §5): a reference run (all generators, the finest grid,
// nearest-surface normals, §3.1-3.3) against a sweep over the generator fraction (§3.1's
// speed-up), the grid resolution, the normal source and the ka encoding (§3.2: ka in the
// normal's length, or a separate attribute). Each preprocessing run is timed whole; its
// foliage normals and per-vertex ka are compared with the reference's. Written as CSV and as
// a chart (error against time).
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "npr/foliage_illumination.h"

namespace sylva {

struct FoliageStudyOptions {
  // Everything but fraction, grid and normals (the sweep's). rho, tau and d_min as given
  // here (auto or not) are resolved once by the reference; every other run then uses the
  // reference's resolved values explicitly (see scale_thresholds), so only the swept
  // parameter changes (auto values would drift with the fraction's random subset and mix
  // effects). seed picks the fraction's leaves.
  FoliageParams base;
  // A random share s of the generators sums to s times the full density in expectation
  // (Eq. 2), so with the reference's tau and d_min unchanged a fraction moves the surface
  // inward and brightens ka, which is not the "very similar result" Luft §3.1 means. True:
  // tau and d_min are the reference's times s = generators / reference generators (exact
  // and deterministic); false: the reference's values as they are.
  bool scale_thresholds = true;
  std::vector<double> fractions = {1, 0.5, 0.25, 0.1, 0.05, 0.01};  // each in (0, 1]
  std::vector<int> grids = {32, 64, 128, 256};                      // cells, each [2, 1024]
  // Both sources depend on the grid (Gradient reads the gradient of the trilinear grid, and
  // ka is the grid's trilinear density for either), so each is run at every grid.
  std::vector<NormalSource> normals = {NormalSource::Surface, NormalSource::Gradient};
  // The encoding changes no preprocessing: each run is evaluated once per encoding.
  std::vector<KaEncoding> encodings = {KaEncoding::Length, KaEncoding::Attribute};
  // The reference's grid; the one used is max(reference_grid, the largest of grids), so no
  // run is finer than the reference. [2, 1024]
  int reference_grid = 256;
  // Called after each preprocessing run (the reference first) with a short description, for
  // progress reports. May be empty.
  std::function<void(const std::string&)> on_run;
};

// Throws InputError (where: fractions, grids, normal-sources, encodings or reference-grid)
// naming the allowed range; also validate_foliage_params(base) with fraction and grid unset.
void validate_foliage_study(const FoliageStudyOptions& options);

// Preprocessing runs a study makes: 1 (the reference) + fractions x grids x normals.
size_t foliage_study_runs(const FoliageStudyOptions& options);

struct FoliageStudyRow {
  double fraction = 1;
  int grid = 0;
  NormalSource normals = NormalSource::Surface;
  KaEncoding encoding = KaEncoding::Length;
  bool reference = false;     // the reference's own parameters (fraction 1, its grid, surface)
  double tau = 0, d_min = 0;  // the thresholds this run used (density units)
  // Empty when the run failed (then `error` says why).
  std::optional<size_t> generators;
  std::optional<double> seconds;  // wall time of the whole preprocessing call
  // Angle between this run's and the reference's normal at each foliage vertex, degrees.
  std::optional<double> normal_mean_deg, normal_p95_deg;
  std::optional<double> ka_rmse;  // per-vertex ka against the reference's, all vertices
  // ka at the centroid of every triangle as the renderer sees it (Length: |interpolated
  // encoded normal|, clamped to [0, 1]; Attribute: interpolated ka) against the reference's
  // interpolated ka. With Length this includes the encoding's own error
  // (normal_length_interpolation_bias), so it is not zero even for the reference.
  std::optional<double> ka_interior_rmse;
  std::string error;  // why the run failed (e.g. no surface at this grid), else empty
};

struct FoliageStudy {
  FoliageStats reference;         // the reference run: resolved rho, tau, d_min; generators
  bool scaled_thresholds = true;  // FoliageStudyOptions::scale_thresholds
  double reference_seconds = 0;
  int reference_grid = 0;
  // Nested in the order fractions > grids > normals > encodings, as given.
  std::vector<FoliageStudyRow> rows;
};

// Needs roles and primitive ids (finish_scene). Throws InputError when the options are out of
// range or the reference itself fails (no foliage, tau above every density); a failing sweep
// run is recorded in its row instead. Deterministic apart from the times.
FoliageStudy run_foliage_study(const Scene& scene, const FoliageStudyOptions& options);

// The CSV text, one row per FoliageStudyRow, header:
// fraction,grid,normals,encoding,reference,generators,tau,d_min,seconds,normal_mean_deg,
// normal_p95_deg,ka_rmse,ka_interior_rmse,error
// Failed runs have empty numeric fields (never NaN) and a quoted error.
std::string foliage_study_csv(const FoliageStudy& study);

// The chart: x = preprocessing time (s, log scale); left panel y = mean normal error
// (degrees), right panel y = ka RMSE; one colour and marker per normal source, one shade and
// line per grid (through its fractions, each point labelled with its fraction), the
// reference marked; title with `scene_name` and the reference's parameters. 8-bit BGR,
// white background; width in [600, 4000], height in [400, 4000].
cv::Mat plot_foliage_study(const FoliageStudy& study, const std::string& scene_name,
                           int width = 1200, int height = 800);

const char* normal_source_name(NormalSource s);  // "surface", "gradient"
const char* ka_encoding_name(KaEncoding e);      // "length", "attribute"

}  // namespace sylva

// The job controller of aggpack-gui: the jobs that run on the worker thread (BackgroundJob, one
// at a time) -- pack the panel's configuration, open a native file, export the shown packing --
// and taking their results back on the window thread (poll_job, each frame). The mesomodel
// export's job is in mesomodel_export.cpp.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/pipeline/pipeline.h"
#include "gui_app.h"
#include "i18n.h"
#include "library_words.h"

namespace aggpack::gui {

namespace {

// Builds the job's packing's scene on the worker (the window uploads it in pieces).
void build_scene(BackgroundJob& job, JobResult& out) {
  job.set_name(tr(Text::kJobBuildingScene));
  job.set_progress(0.0);
  job.set_detail(trs(Text::kJobParticles, out.packing->particles.size()));
  out.scene = prepare_scene(*out.packing, [&job](double fraction) { job.set_progress(fraction); });
}

}  // namespace

void GuiApp::start_pack() {
  if (job_.is_running()) return;
  // Validate on this thread so a bad field is reported at once, with the CLI's message.
  PackConfig config;
  update_field_errors();
  try {
    config = fields_.build();
  } catch (const Error& error) {
    set_status(error_words(error), true);
    if (script_.is_waiting_for_first_job()) exit_code_ = 2;
    return;
  }
  set_status(tr(Text::kStatusPacking), false);
  job_entries_ = fields_.set_entries();
  job_kind_ = "pack";
  job_.start(tr(Text::kJobPacking), [config](BackgroundJob& job) {
    PackControl control;
    control.cancel = job.cancel_flag();
    control.progress_interval = 0.05;
    control.on_progress = [&job](const PackProgress& progress) {
      job.set_progress(progress.fraction);
      // The lattice kind measures the volume at the end only: no live solid fraction.
      const std::string solid = progress.solid_fraction > 0.0
                                    ? trs(Text::kProgressSolid, 100.0 * progress.solid_fraction)
                                    : std::string();
      job.set_detail(
          trs(progress.stage == PackStage::kDensify ? Text::kProgressSweep : Text::kProgressPlaced,
              progress.placed, progress.total, solid));
    };
    PipelineResult result = pack(config, control);
    JobResult out;
    const bool is_cancelled = result.report.stop_reason == StopReason::kCancelled;
    out.is_ok = true;
    // Every line from the reports' numbers, in the window's language (library_words.h).
    out.message = trs(is_cancelled ? Text::kPackCancelled : Text::kPackFinished,
                      result.packing.particles.size(), 100.0 * result.report.solid_fraction) +
                  "\n" +
                  (result.fill ? tr(Text::kFillPrefix) + report_words(result.fill->report)
                               : report_words(result.report));
    // The dense kind: the densifier, the asked fraction, and what fell short of it.
    if (result.densify)
      out.message += "\n" + (tr(Text::kDensifyPrefix) + densify_words(*result.densify));
    if (result.fill && result.fill->asked_fraction > 0) {
      out.message += trs(Text::kAskedFraction, 100.0 * result.fill->asked_fraction);
    }
    for (const std::string& line : shortfall_words(result)) {
      out.message += "\n" + (tr(Text::kWarningPrefix) + line);
    }
    out.packing = std::make_shared<const Packing>(std::move(result.packing));
    build_scene(job, out);
    return out;
  });
}

void GuiApp::start_open(const std::string& path) {
  if (job_.is_running()) return;
  set_status(trs(Text::kStatusOpening, path), false);
  job_kind_ = "open";
  job_.start(tr(Text::kJobOpening), [path](BackgroundJob& job) {
    JobResult out;
    auto packing = std::make_shared<const Packing>(read_packing(path));
    out.is_ok = true;
    double solid = 0.0;
    for (std::size_t i = 0; i < packing->particles.size(); ++i) {
      solid += mass_properties(packing->local_body(i)).volume;
    }
    const double volume = packing->container.volume();
    out.message = trs(Text::kOpened, path, packing->particles.size(),
                      volume > 0 ? 100.0 * solid / volume : 0.0);
    out.config_toml = packing->provenance.config_toml;
    out.packing = std::move(packing);
    build_scene(job, out);
    return out;
  });
}

void GuiApp::start_export(const std::string& format, DeckKind deck, const std::string& path) {
  if (job_.is_running() || !packing_) return;
  ExportOptions options{.format = parse_export_format(format), .overwrite = Overwrite::kAllow};
  if (deck != DeckKind::kNone) {  // a complete solver model around the mesh (export --deck)
    options.deck = deck_options_;
    options.deck.kind = deck;
    options.material = deck_material_;
  }
  try {  // the fields' errors at once, before the job
    validate(options, options.format);
  } catch (const Error& error) {
    set_status(error_words(error), true);
    return;
  }
  set_status(trs(Text::kStatusWriting, path), false);
  const std::string what =
      deck == DeckKind::kNone ? std::string() : deck_title(deck) + tr(Text::kListSeparator);
  job_.start(tr(Text::kJobExporting), [packing = packing_, options, path, what](BackgroundJob&) {
    JobResult out;
    const ExportSummary summary = write(*packing, path, options);
    out.message = trs(Text::kWrote, path, what, summary.particles, summary.nodes, summary.elements);
    out.is_ok = true;
    return out;
  });
}

void GuiApp::poll_job() {
  JobResult result;
  if (!job_.take_result(result)) return;
  std::string message = result.message;
  std::vector<std::string> entries = job_entries_;
  if (!result.config_toml.empty()) {
    // An opened file: its stored configuration fills the panel, so Pack repeats or varies it.
    try {
      fields_ = ConfigFields::from_config(parse_pack_config(result.config_toml, "stored config"));
      message += tr(Text::kOpenedConfig);
    } catch (const Error&) {
      message += tr(Text::kOpenedConfigBad);
    }
  }
  if (result.packing && job_kind_ == "open") entries = fields_.set_entries();
  set_status(message, !result.is_ok);
  if (result.packing) show_packing(result.packing, result.scene, std::move(entries));
  script_.on_job_result(result);
}

}  // namespace aggpack::gui

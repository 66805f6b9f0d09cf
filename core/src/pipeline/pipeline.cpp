#include "kew/pipeline/pipeline.hpp"

#include <stdexcept>

#include "alert_stage.hpp"
#include "batch.hpp"
#include "kew/pipeline/instrumentation.hpp"
#include "kew/pipeline/pair_observer.hpp"
#include "kew/util/worker_pool.hpp"
#include "pair_judge.hpp"
#include "phase_timer.hpp"
#include "track_stage.hpp"
#include "zone_set.hpp"

namespace kew {

Pipeline::Pipeline(const PipelineConfig& config)
    : config_(config),
      instruments_(std::make_unique<PipelineInstrumentation>()),
      phases_(std::make_unique<PhaseTimes>()),
      judge_(std::make_unique<pipeline::PairJudge>(config_)),
      batch_(std::make_unique<pipeline::Batch>()),
      zones_(std::make_unique<pipeline::ZoneSet>(config_, *judge_, *instruments_)),
      track_(std::make_unique<pipeline::TrackStage>(config_, *zones_, *batch_, judge_->regions())),
      alert_(std::make_unique<pipeline::AlertStage>(config_, *judge_, *zones_, *instruments_, track_->tracks())),
      prompt_left_(config.prompt_records) {
  if (config_.threads > 1) pool_ = std::make_unique<util::WorkerPool>(config_.threads);
}

Pipeline::~Pipeline() = default;

void Pipeline::set_alert_sink(AlertSink sink) { alert_->set_sink(std::move(sink)); }
void Pipeline::instrument(const PipelineInstrumentation& instruments) { *instruments_ = instruments; }
const PhaseTimes& Pipeline::phase_times() const { return *phases_; }
void Pipeline::set_time_ceiling(double utc_s) { track_->set_time_ceiling(utc_s); }

void Pipeline::set_pair_observer(PairObserver* observer) {
  if (observer && config_.batch_records != 1) throw std::invalid_argument("a pair observer needs batch_records = 1");
  observer_ = observer;
  track_->set_pair_observer(observer);
  alert_->set_pair_observer(observer);
}

RecordOutcome Pipeline::process(const TrackReport& report) {
  const track::Refusal refusal = track_->screen(report);
  if (refusal != track::Refusal::None) {
    const RecordOutcome refused{RecordOutcome::Kind::Refused, refusal};
    observe_refusal(report, refused);
    return refused;
  }
  const RecordOutcome outcome = track_->process(report);
  if (track_->young_run_stuck()) restart_young_run();
  if (prompt_left_ > 0) {
    --prompt_left_;
    run_batch();
  } else if (batch_->steps.size() >= config_.batch_records) {
    run_batch();
  }
  // After the batch: the alert stage has judged what the track stage took meanwhile.
  if (outcome.kind == RecordOutcome::Kind::Refused) observe_refusal(report, outcome);
  return outcome;
}

void Pipeline::observe_refusal(const TrackReport& report, const RecordOutcome& refused) {
  if (observer_ && observer_->watches(report.source, report.id)) observer_->record(report, refused);
}

void Pipeline::restart_young_run() {
  std::vector<TrackReport> refused = track_->take_young_refused();
  drop_all();
  for (const TrackReport& r : track_->restart(std::move(refused))) track_->process(r);
}

void Pipeline::end_of_input() {
  track_->end_of_input();
  flush();
}

void Pipeline::flush() {
  run_batch();
  prompt_left_ = config_.prompt_records;
}

bool Pipeline::batch_waiting() const { return !batch_->steps.empty() || zones_->has_work(); }

void Pipeline::advance_to(double t) {
  if (track_->advance_to(t)) flush();
}

void Pipeline::drop_all() {
  track_->drop_all();
  flush();
}

void Pipeline::run_batch() {
  if (!zones_->has_work() && batch_->steps.empty()) return;
  zones_->run(batch_->snapshots, track_->now(), pool_.get(), *phases_);
  pipeline::timed(instruments_->time_phases, *phases_, &PhaseTimes::tests_s, [&] { alert_->run(*batch_); });
  zones_->end_batch();
  batch_->clear();
}

kinetic::KineticAudit Pipeline::audit() {
  flush();
  return zones_->audit(track_->now());
}

bool Pipeline::is_valid() const { return zones_->is_valid(); }
double Pipeline::now() const { return track_->now(); }

PipelineStatistics Pipeline::statistics() const {
  PipelineStatistics s = track_->statistics();
  s.probes = alert_->probes();
  s.candidates = alert_->candidates();
  s.zones_created = zones_->zones_created();
  s.zones_retired = zones_->zones_retired();
  return s;
}

kinetic::KineticStatistics Pipeline::kinetic_statistics() const { return zones_->kinetic_statistics(); }
const Rejections& Pipeline::rejections() const { return track_->tracks().rejections(); }
Rejections& Pipeline::rejections() { return track_->tracks().rejections(); }
const Rejections& Pipeline::dropped_fields() const { return track_->tracks().dropped_fields(); }
Rejections& Pipeline::dropped_fields() { return track_->tracks().dropped_fields(); }
const Rejections& Pipeline::suppressed() const { return alert_->suppressed(); }
const track::TrackTable& Pipeline::tracks() const { return track_->tracks(); }
std::size_t Pipeline::live_tracks() const { return track_->live_tracks(); }
const alert::AlertManager& Pipeline::alerts() const { return alert_->alerts(); }
alert::AlertManager& Pipeline::alerts() { return alert_->alerts(); }
const std::optional<geo::Projection>& Pipeline::projection() const { return zones_->single_plane(); }

void Pipeline::for_each_zone(const std::function<void(const zone::Zone&)>& f) const { zones_->for_each_zone(f); }
std::size_t Pipeline::zone_count() const { return zones_->zone_count(); }
const zone::Zone* Pipeline::home_zone(track::TrackSlot slot) const { return zones_->home_zone(track_->tracks()[slot]); }
const std::optional<zone::ZoneTiling>& Pipeline::tiling() const { return zones_->tiling(); }
double Pipeline::zone_margin_m() const { return zones_->margin_m(); }

}  // namespace kew

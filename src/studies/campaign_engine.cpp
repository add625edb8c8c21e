#include "studies/campaign_engine.hpp"

#include <sched.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <deque>
#include <ostream>
#include <set>

namespace biped {
namespace {

using Clock = std::chrono::steady_clock;

std::string host_name() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

// The first key holding a NaN or an infinity, or "".
std::string non_finite_key(const nlohmann::json& value, const std::string& path) {
  if (value.is_number_float() && !std::isfinite(value.get<double>())) return path.empty() ? "(value)" : path;
  if (value.is_object()) {
    for (const auto& [key, item] : value.items()) {
      const std::string found = non_finite_key(item, path.empty() ? key : path + "." + key);
      if (!found.empty()) return found;
    }
  }
  if (value.is_array()) {
    for (std::size_t i = 0; i < value.size(); ++i) {
      const std::string found = non_finite_key(value[i], path + "." + std::to_string(i));
      if (!found.empty()) return found;
    }
  }
  return "";
}

// One item, never throwing: an exception or a non-finite number becomes an error row.
CampaignRow run_item(const CampaignWork& work, long index, const std::string& host, int rank) {
  const auto start = Clock::now();
  CampaignRow row;
  try {
    row = work.describe(index);
    row.run = index;
    work.run(index, row);
    const std::string bad = non_finite_key(row.result, "");
    if (bad.empty()) {
      row.status = "ok";
    } else {
      row.status = "error";
      row.error = "non-finite value in the result: " + bad;
    }
  } catch (const std::exception& e) {
    row.run = index;
    row.status = "error";
    row.error = e.what();
  }
  row.wall_time_s = std::chrono::duration<double>(Clock::now() - start).count();
  row.host = host;
  row.rank = rank;
  return row;
}

nlohmann::json to_json(const CampaignRow& r) {
  return {{"run", r.run},       {"status", r.status},   {"error", r.error},        {"parameters", r.parameters},
          {"command", r.command}, {"result", r.result}, {"wall_time_s", r.wall_time_s}, {"host", r.host},
          {"rank", r.rank}};
}

CampaignRow from_json(const nlohmann::json& j) {
  CampaignRow r;
  r.run = j["run"];
  r.status = j["status"];
  r.error = j["error"];
  r.parameters = j["parameters"];
  r.command = j["command"];
  r.result = j["result"];
  r.wall_time_s = j["wall_time_s"];
  r.host = j["host"];
  r.rank = j["rank"];
  return r;
}

// The coordinator's progress line: done/total, rate, ETA, survival so far.
class Progress {
 public:
  Progress(std::ostream* out, std::string label, long total, long before)
      : out_(out), label_(std::move(label)), total_(total), before_(before), start_(Clock::now()),
        tty_(out && isatty(STDERR_FILENO)) {}

  void add(const CampaignRow& row) {
    ++done_;
    if (row.status != "ok") ++errors_;
    if (row.result.contains("fell") && row.result["fell"].is_boolean()) {
      ++judged_;
      if (!row.result["fell"].get<bool>()) ++survived_;
    }
    show(false);
  }

  void show(bool last) {
    if (!out_) return;
    const auto now = Clock::now();
    // A log file gets a line only when something finished.
    if (!last && (done_ == 0 || now - shown_ < std::chrono::seconds(tty_ ? 1 : 5) || (!tty_ && done_ == shown_done_))) return;
    shown_ = now;
    shown_done_ = done_;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double rate = elapsed > 0.0 ? done_ / elapsed : 0.0;
    const long left = total_ - before_ - done_;
    char line[256];
    std::snprintf(line, sizeof line, "%s: %ld/%ld done, %.2f/s, ETA %s", label_.c_str(), before_ + done_, total_, rate,
                  rate > 0.0 ? (std::to_string(static_cast<long>(left / rate + 0.5)) + " s").c_str() : "?");
    std::string text = line;
    if (judged_ > 0) {
      std::snprintf(line, sizeof line, ", survival %.1f %% (%ld/%ld)", 100.0 * survived_ / judged_, survived_, judged_);
      text += line;
    }
    if (errors_ > 0) text += ", " + std::to_string(errors_) + " errors";
    if (before_ > 0) text += " (" + std::to_string(before_) + " from before)";
    *out_ << (tty_ ? "\r" : "") << text << (tty_ && !last ? "\033[K" : "\n") << std::flush;
  }

 private:
  std::ostream* out_;
  std::string label_;
  long total_, before_, done_ = 0, errors_ = 0, judged_ = 0, survived_ = 0, shown_done_ = 0;
  Clock::time_point start_, shown_{};
  bool tty_;
};

// Items handed out and results coming back, shared by the coordinator's thread and its workers.
class Dispatch {
 public:
  explicit Dispatch(std::vector<long> pending) : pending_(pending.begin(), pending.end()) {}

  bool next(long& index) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (pending_.empty()) return false;
    index = pending_.front();
    pending_.pop_front();
    return true;
  }
  // Hands out nothing more (the coordinator failed; its workers end after their current item).
  void cancel() {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.clear();
  }
  void finish(CampaignRow row) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      results_.push_back(std::move(row));
    }
    ready_.notify_one();
  }
  std::vector<CampaignRow> take(std::chrono::milliseconds wait) {
    std::unique_lock<std::mutex> lock(mutex_);
    ready_.wait_for(lock, wait, [&] { return !results_.empty(); });
    std::vector<CampaignRow> out(std::make_move_iterator(results_.begin()), std::make_move_iterator(results_.end()));
    results_.clear();
    return out;
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<long> pending_;
  std::deque<CampaignRow> results_;
};

// A worker on a rank other than 0: ask for an item (sending the last result along), run it, repeat.
void remote_worker(const CampaignWork& work, const MpiSession& mpi, int tag, const std::string& host) {
  nlohmann::json request = {{"result", nullptr}};
  for (;;) {
    mpi.send(0, tag, request.dump());
    const nlohmann::json reply = nlohmann::json::parse(mpi.receive(0, tag));
    if (reply.contains("stop")) return;
    request["result"] = to_json(run_item(work, reply["run"].get<long>(), host, mpi.rank()));
  }
}

}  // namespace

int available_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

CampaignEngineOutcome run_campaign_engine(const CampaignWork& work, const std::string& database_path,
                                          const MpiSession& mpi, const CampaignEngineOptions& options) {
  const auto start = Clock::now();
  const std::string host = host_name();
  int jobs = options.jobs > 0 ? options.jobs : (mpi.active() ? 1 : available_cores());
  if (mpi.rank() != 0 && !mpi.threads_may_communicate()) jobs = 1;
  const std::vector<int> jobs_per_rank = mpi.gather(jobs);

  CampaignEngineOutcome outcome;
  outcome.ranks = mpi.size();
  outcome.total = work.size();
  if (mpi.rank() != 0) {
    outcome.coordinator = false;
    std::vector<std::thread> threads;
    for (int t = 1; t < jobs; ++t) threads.emplace_back([&, t] { remote_worker(work, mpi, t, host); });
    remote_worker(work, mpi, 0, host);
    for (std::thread& t : threads) t.join();
    return outcome;
  }

  CampaignDatabase database(database_path);
  database.claim(work.identity(), work.size());
  const std::set<long> finished = database.finished_runs();
  std::vector<long> pending;
  for (long i = 0; i < work.size(); ++i) {
    if (!finished.count(i)) pending.push_back(i);
  }
  outcome.finished_before = static_cast<long>(finished.size());
  int remote_workers = 0;
  for (std::size_t r = 1; r < jobs_per_rank.size(); ++r) remote_workers += jobs_per_rank[r];
  outcome.workers = jobs + remote_workers;

  Dispatch dispatch(pending);
  Progress progress(options.progress, options.label, work.size(), outcome.finished_before);
  auto store = [&](const CampaignRow& row) {
    const auto begin = Clock::now();
    database.insert(row);
    outcome.storing_s += std::chrono::duration<double>(Clock::now() - begin).count();
    progress.add(row);
    ++outcome.ran;
  };
  std::vector<std::thread> threads;
  const int local_workers = static_cast<int>(std::min<long>(jobs, static_cast<long>(pending.size())));
  for (int t = 0; t < local_workers; ++t) {
    threads.emplace_back([&] {
      long index = 0;
      while (dispatch.next(index)) dispatch.finish(run_item(work, index, host, 0));
    });
  }
  // The coordinator's loop: store local results; under MPI answer the other ranks' requests, each
  // remote worker getting exactly one `stop` once nothing is left.
  int stops_sent = 0;
  const auto wait = std::chrono::milliseconds(mpi.active() ? 1 : 200);
  try {
    while (outcome.ran < static_cast<long>(pending.size()) || stops_sent < remote_workers) {
      for (const CampaignRow& row : dispatch.take(wait)) store(row);
      int source = 0, tag = 0;
      while (mpi.active() && mpi.poll(source, tag)) {
        const auto begin = Clock::now();
        const nlohmann::json request = nlohmann::json::parse(mpi.receive(source, tag));
        outcome.storing_s += std::chrono::duration<double>(Clock::now() - begin).count();
        if (!request["result"].is_null()) store(from_json(request["result"]));
        long index = 0;
        if (dispatch.next(index)) {
          mpi.send(source, tag, nlohmann::json{{"run", index}}.dump());
        } else {
          mpi.send(source, tag, R"({"stop": true})");
          ++stops_sent;
        }
      }
      progress.show(false);
    }
  } catch (...) {
    // A failure to store (disk full, database locked) ends the campaign with its message; the
    // worker threads finish their items first (a thread left running would abort the program).
    dispatch.cancel();
    for (std::thread& t : threads) t.join();
    throw;
  }
  for (std::thread& t : threads) t.join();
  progress.show(true);
  outcome.wall_time_s = std::chrono::duration<double>(Clock::now() - start).count();
  return outcome;
}

}  // namespace biped

// The run's times, threads and host, beside its output (run_record.h).
#include "run_record.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "command_registry.h"
#include "prt/core/atomic_file.h"
#include "prt/core/memory_budget.h"

namespace prt::cli {
namespace {

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "";
  return name;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  if (::gmtime_r(&now, &tm) == nullptr) return "";
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

}  // namespace

RunRecord& run_record() {
  static RunRecord record;
  return record;
}

int resolved_threads(int requested) {
  if (requested > 0) return requested;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::string run_record_path(const std::string& output) {
  return output + ".run.json";
}

void write_run_record(const std::string& output, const std::string& command_line,
                      const std::string& version, double seconds) {
  const RunRecord& r = run_record();
  nlohmann::ordered_json j;  // in the order above
  j["command"] = command_line;
  j["output"] = output;
  j["prt_version"] = version;
  j["host"] = host_name();
  j["finished_utc"] = utc_now();
  if (r.threads > 0) j["threads"] = r.threads;
  j["seconds"] = seconds;
  nlohmann::ordered_json phases = nlohmann::ordered_json::object();
  for (const auto& [name, s] : r.phases) phases[name] = s;
  j["phase_seconds"] = phases;
  if (!r.cpu_phases.empty()) {
    nlohmann::ordered_json cpu = nlohmann::ordered_json::object();
    for (const auto& [name, s] : r.cpu_phases) cpu[name] = s;
    j["phase_cpu_seconds"] = cpu;
  }
  j["peak_resident_bytes"] = prt::peak_resident_bytes();
  const std::string text = j.dump(2) + "\n";
  const std::string path = run_record_path(output);
  const prt::Status written = prt::write_file_atomically(path, text.data(), text.size());
  if (!written.ok()) {
    std::remove(path.c_str());  // an older record would describe another run of OUT
    throw CommandError(written.message());
  }
}

// FILE.run.json parsed as Json (ordered or not), null when absent.
template <class Json>
Json read_record(const std::string& file) {
  std::ifstream in(run_record_path(file), std::ios::binary);
  if (!in) return nullptr;
  std::stringstream text;
  text << in.rdbuf();
  Json j = Json::parse(text.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object())
    return Json{{"unreadable", run_record_path(file) + " is not a JSON object"}};
  return j;
}

nlohmann::json read_run_record(const std::string& file) {
  return read_record<nlohmann::json>(file);
}

void add_run_record_json(nlohmann::json& j, const std::string& file) {
  nlohmann::json record = read_run_record(file);
  if (!record.is_null()) j["run"] = std::move(record);
}

void print_run_record(const std::string& file) {
  const nlohmann::ordered_json j = read_record<nlohmann::ordered_json>(file);  // phases in order
  if (j.is_null()) {
    std::printf("run           not recorded (%s is absent)\n", run_record_path(file).c_str());
    return;
  }
  if (j.contains("unreadable")) {
    std::printf("run           %s\n", j["unreadable"].get<std::string>().c_str());
    return;
  }
  const auto number = [&j](const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : 0.0;
  };
  const auto text = [&j](const char* key) {
    return j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string("?");
  };
  // Numbers printed as doubles or range-checked first: a hand-edited record may hold any value.
  std::printf("run           %.2f s", number("seconds"));
  if (j.contains("threads")) std::printf(" on %.0f thread(s)", number("threads"));
  const double peak = number("peak_resident_bytes");
  const uint64_t peak_bytes = peak > 0 && peak < 1e18 ? static_cast<uint64_t>(peak) : 0;
  std::printf(", host %s, %s, peak resident %s (from %s)\n", text("host").c_str(),
              text("finished_utc").c_str(), prt::format_memory_size(peak_bytes).c_str(),
              run_record_path(file).c_str());
  if (j.contains("phase_seconds") && j["phase_seconds"].is_object())
    for (const auto& [name, s] : j["phase_seconds"].items())
      if (s.is_number()) std::printf("  %-28s %.2f s\n", name.c_str(), s.get<double>());
  std::printf("command       %s\n", text("command").c_str());
}

}  // namespace prt::cli

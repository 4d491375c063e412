// What `geombake bake` leaves when its inputs are done (bake_report.h).
#include "geombake/bake_report.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "geom/atomic_file.h"
#include "geom/version.h"
#include "geombake/fault.h"
#include "geombake/names.h"
#include "geombake/sha256.h"

namespace geombake {
namespace fs = std::filesystem;
namespace {

std::string normal(const std::string& path) {
  std::error_code ec;
  return fs::weakly_canonical(fs::absolute(path, ec), ec).lexically_normal().string();
}

// The .gbake files under `dir` (symlinks not followed) that are not in `keep`.
std::vector<std::string> unclaimed(const std::string& dir, const std::set<std::string>& keep) {
  std::vector<std::string> found;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    const std::string name = p.filename().string();
    if (name.size() <= 6 || name.compare(name.size() - 6, 6, ".gbake") != 0) continue;
    const fs::file_type t = it->symlink_status(ec).type();
    if ((t == fs::file_type::regular || t == fs::file_type::symlink) && !keep.count(normal(p.string())))
      found.push_back(p.string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace

bool settle_outputs(std::vector<Job>& jobs, const BakeConfig& config, std::vector<std::string>& pruned) {
  bool ok = true;
  std::set<std::string> keep;  // every output this run maps an input to, and every file an input reads
  for (Job& job : jobs) {
    keep.insert(normal(job.output));
    for (const std::string& file : job.reads) keep.insert(normal(file));
    if (job.done || job.kind == ErrorKind::OutputConflict) continue;  // a conflict's output is another input's
    struct stat st {};
    if (::lstat(job.output.c_str(), &st) != 0 || S_ISDIR(st.st_mode)) continue;  // none, or not a file of ours
    if (::unlink(job.output.c_str()) != 0 && errno != ENOENT) {
      std::fprintf(stderr, "Error: %s: cannot remove the stale output %s: %s\n", job.input.c_str(), job.output.c_str(),
                   std::strerror(errno));
      ok = false;
    }
  }
  if (!config.prune || !config.out_is_dir) return ok;
  for (const std::string& path : unclaimed(config.out, keep)) {
    if (::unlink(path.c_str()) == 0) {
      pruned.push_back(path);
    } else if (errno != ENOENT) {
      std::fprintf(stderr, "Error: --prune: cannot remove %s: %s\n", path.c_str(), std::strerror(errno));
      ok = false;
    }
  }
  return ok;
}

namespace {

// Characters Make (or Ninja) misread in a depfile name, with who misreads them.
const struct {
  char c;
  const char* name;
  const char* who;
} kDepfileHazards[] = {
    {':', "':'", "Make (a second rule separator)"},
    {';', "';'", "Make (starts a recipe)"},
    {'%', "'%'", "Make (a pattern)"},
    {'\t', "a tab", "Make and Ninja (no escape for it)"},
};

// `path` escaped for the depfile (names.h make_escape), a warning for each hazard.
bool depfile_name(const std::string& path, const std::string& input, std::string& escaped, std::string& problems,
                  std::string& warnings) {
  if (!make_escape(path, escaped)) {
    const std::string line = "Error: " + input + ": a newline in its name or its output's cannot be written in a " +
                             "depfile (Make and Ninja have no escape for it)\n";
    if (problems.find(line) == std::string::npos) problems += line;
    return false;
  }
  for (const auto& h : kDepfileHazards)
    if (path.find(h.c) != std::string::npos)
      warnings += "Warning: --depfile: the name " + path + " holds " + h.name + ", which " + h.who +
                  " cannot read in a depfile: a build that reads it may fail or miss this dependency\n";
  return true;
}

}  // namespace

std::string depfile_text(const std::vector<Job>& jobs, const BakeConfig& config, std::string& problems,
                         std::string& warnings) {
  std::string text, all, escaped;
  std::set<std::string> listed, warned;
  auto add = [&](const std::string& path, const std::string& input, std::string& to) {
    std::string w;
    if (!depfile_name(path, input, escaped, problems, w)) return false;
    if (!w.empty() && warned.insert(path).second) warnings += w;
    to += " " + escaped;
    return true;
  };
  const bool one_rule = !config.depfile_target.empty();
  for (const Job& job : jobs) {
    if (job.kind == ErrorKind::OutputConflict) continue;  // its output is another input's
    const std::vector<std::string>& deps = job.reads;
    if (one_rule) {
      for (const std::string& d : deps)
        if (listed.insert(d).second) add(d, job.input, all);
      continue;
    }
    std::string target, read;
    bool ok = add(job.output, job.input, target);
    for (const std::string& d : deps) ok = add(d, job.input, read) && ok;
    if (ok) text += target.substr(1) + ":" + read + "\n";
  }
  std::string target;
  if (one_rule && add(config.depfile_target, "--depfile-target", target)) text = target.substr(1) + ":" + all + "\n";
  return text;
}

namespace {

nlohmann::ordered_json section_json(const SectionInfo& s) {
  return {{"name", s.name},
          {"type", geom::baked::type_name(s.type)},
          {"format", geom::baked::format_name(s.format)},
          {"item", s.item},
          {"stride", s.stride},
          {"count", s.count},
          {"bytes", s.bytes},
          {"crc32c", s.crc}};
}

// One input's entry in --json and the -r report. --stable-report leaves out
// what changes from run to run on the same inputs ("written", "seconds").
nlohmann::ordered_json job_json(const Job& job, bool stable) {
  nlohmann::ordered_json j = {{"input", job.input}, {"output", job.output}, {"ok", job.done}};
  if (!job.done) j["error"] = job.error, j["error_kind"] = error_kind_name(job.kind);
  nlohmann::ordered_json reads = nlohmann::ordered_json::array();
  for (const std::string& file : job.reads) reads.push_back({{"file", file}, {"sha256", file_sha256(file)}});
  j["sha256"] = reads[0]["sha256"];
  j["reads"] = std::move(reads);
  if (!stable) j["seconds"] = double(int64_t(job.seconds * 1e6)) * 1e-6;
  if (!job.done) return j;
  if (!stable) j["written"] = job.written == Written::New;
  j["warnings"] = job.warnings;
  uint64_t total = 0;
  j["sections"] = nlohmann::ordered_json::array();
  for (const auto& s : job.sections) {
    j["sections"].push_back(section_json(s));
    total += s.bytes;
  }
  j["section_bytes"] = total;
  j["topology"] = json_text(geom::report_json(job.result.report));  // any name in it (names.h)
  if (!job.result.silhouette.empty()) j["silhouette"] = json_text(job.result.silhouette);
  return j;
}

// -v: sections, bytes and topology of one baked input on stdout.
void print_verbose(const Job& job, const geom::BakeOptions& options) {
  uint64_t total = 0;
  for (const auto& s : job.sections) total += s.bytes;
  std::printf("%s -> %s: %zu sections, %llu bytes of buffers%s\n", job.input.c_str(), job.output.c_str(),
              job.sections.size(), (unsigned long long)total,
              job.written == Written::Unchanged ? " (unchanged, left untouched)" : "");
  for (const auto& s : job.sections)
    std::printf("  %-13s %-4u %-7s %10llu x %-3u = %12llu bytes\n", s.name.c_str(), s.item,
                geom::baked::format_name(s.format), (unsigned long long)s.count, s.stride, (unsigned long long)s.bytes);
  const geom::EsmStats& e = job.result.esm;
  const geom::ShadowVolumeStats& sv = job.result.volume;
  if (options.pipeline.esm)
    std::printf(
        "  esm         %llu quads on %llu of %llu candidate edges (%llu coplanar, %llu concave skipped), "
        "%llu bytes against %llu naive\n",
        (unsigned long long)e.quads, (unsigned long long)e.emitted_edges, (unsigned long long)e.candidate_edges,
        (unsigned long long)e.skipped_coplanar, (unsigned long long)e.skipped_concave, (unsigned long long)e.bytes,
        (unsigned long long)e.naive_bytes);
  if (options.pipeline.volume)
    std::printf("  volume      %llu sides, %llu caps (%llu coplanar edges skipped), %llu bytes against %llu naive\n",
                (unsigned long long)sv.sides, (unsigned long long)sv.caps, (unsigned long long)sv.skipped_coplanar,
                (unsigned long long)sv.bytes, (unsigned long long)sv.naive_bytes);
  std::fputs(geom::report_text(job.result.report).c_str(), stdout);
}

// Writes `text` to `path` atomically; false after an `Error:` line.
bool write_or_say(const std::string& path, const std::string& text) {
  std::string error;
  if (geom::write_file_atomically(path, text, error)) return true;
  std::fprintf(stderr, "Error: %s\n", error.c_str());
  return false;
}

struct Counts {
  size_t failed = 0, unchanged = 0;
};

void print_summary(const std::vector<Job>& jobs, const Counts& n, const ScheduleStats& stats,
                   const std::vector<std::string>& pruned, int64_t t0_ns) {
  std::fprintf(stderr, "geombake bake: %zu baked, %zu failed of %zu inputs", jobs.size() - n.failed, n.failed,
               jobs.size());
  if (n.unchanged) std::fprintf(stderr, " (%zu unchanged, left untouched)", n.unchanged);
  if (stats.timed_out) std::fprintf(stderr, " (%zu timed out)", stats.timed_out);
  if (!pruned.empty()) std::fprintf(stderr, " (%zu pruned)", pruned.size());
  std::fprintf(stderr, " in %.2f s with %u thread%s\n", double(now_ns() - t0_ns) * 1e-9, stats.threads,
               stats.threads == 1 ? "" : "s");
}

}  // namespace

int report_run(std::vector<Job>& jobs, const BakeConfig& config, const ScheduleStats& stats, int64_t t0_ns) {
  std::vector<std::string> pruned;
  int status = settle_outputs(jobs, config, pruned) ? 0 : 1;
  Counts n;
  nlohmann::ordered_json results = nlohmann::ordered_json::array();
  for (const Job& job : jobs) {
    n.failed += !job.done;
    n.unchanged += job.done && job.written == Written::Unchanged;
    if (config.json || !config.report.empty()) {
      nlohmann::ordered_json j = job_json(job, config.stable);
      if (config.json) std::printf("%s\n", dump_json(j).c_str());  // any name (names.h)
      if (!config.report.empty()) results.push_back(std::move(j));
    }
    if (!config.json && config.verbose && job.done) print_verbose(job, config.options);
  }
  if (n.failed) status = 1;
  if (!config.depfile.empty()) {
    std::string problems, warnings;
    const std::string text = depfile_text(jobs, config, problems, warnings);
    if (!config.quiet) std::fputs(warnings.c_str(), stderr);
    if (!problems.empty()) std::fputs(problems.c_str(), stderr), status = 1;
    if (!write_or_say(config.depfile, text)) status = 1;
  }
  if (!config.report.empty()) {
    nlohmann::ordered_json report = {
        {"geombake", GEOM_VERSION}, {"output", config.out}, {"inputs", jobs.size()}, {"baked", jobs.size() - n.failed}};
    if (!config.stable) report["unchanged"] = n.unchanged;
    report["failed"] = n.failed;
    report["timed_out"] = stats.timed_out;
    report["skipped"] = config.skipped;
    report["pruned"] = pruned;
    report["results"] = std::move(results);
    if (!write_or_say(config.report, dump_json(report, 1) + "\n")) status = 1;
  }
  if (!config.quiet && (jobs.size() > 1 || config.verbose)) print_summary(jobs, n, stats, pruned, t0_ns);
  return status;
}

}  // namespace geombake

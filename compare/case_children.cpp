#include "compare/case_children.hpp"

#include <fcntl.h>
#include <fmt/core.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <deque>
#include <memory>
#include <optional>

#include "model/errors.hpp"

extern char** environ;

namespace rastercmp {
namespace {

using Clock = std::chrono::steady_clock;
constexpr int kResultFd = 3;               // the pipe's number in the child
constexpr size_t kOutputKept = 16 * 1024;  // bytes of a child's stdout + stderr kept for messages
constexpr size_t kOutputLines = 8;         // lines of it quoted in a Crash / Timeout message
constexpr double kStartupS = 60;           // a child's start (Vulkan device) before its first case

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

// A close-on-exec descriptor above the standard ones, so that dup2 onto 1, 2 or 3 in the child
// always clears the flag.
int high_fd(int fd) {
  const int moved = fcntl(fd, F_DUPFD_CLOEXEC, 10);
  close(fd);
  if (moved < 0) throw std::runtime_error(std::string("fcntl: ") + std::strerror(errno));
  return moved;
}

struct Pipe {
  int read = -1, write = -1;
  Pipe() {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    read = high_fd(fds[0]);
    write = high_fd(fds[1]);
  }
};

std::string describe_status(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = sigabbrev_np(sig);
    return fmt::format("killed by signal {} (SIG{}, {})", sig, name ? name : "?", strsignal(sig));
  }
  return fmt::format("exited with code {}", WEXITSTATUS(status));
}

struct Child {
  pid_t pid = -1;
  int result_fd = -1, output_fd = -1;
  std::vector<ChildCase> batch;
  std::vector<bool> begun, recorded;
  std::optional<size_t> current;  // position in batch of the case running
  Clock::time_point started, case_started;
  std::string result_buffer, output;
  bool timed_out = false, told_to_stop = false, recorded_any = false;
  std::string broken;   // what the child wrote on the result pipe that is not the protocol's; killed for it
  bool exited = false;  // reaped (waitpid); `status` is its wait status
  int status = 0;
};

void close_fd(int& fd) {
  if (fd >= 0) close(fd);
  fd = -1;
}

// The child's process group (its pid: spawn makes it the leader), helpers included.
void kill_group(const Child& c) {
  if (c.pid > 0) kill(-c.pid, SIGKILL);
}

std::unique_ptr<Child> spawn(const ChildRunOptions& o, std::vector<ChildCase> batch) {
  auto child = std::make_unique<Child>();
  Pipe result, output;
  std::vector<std::string> args = o.command;
  args.insert(args.end(), {"--report", o.report_dir, "--result-fd", std::to_string(kResultFd), "--"});
  for (const ChildCase& c : batch) args.push_back(c.scene_file);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, output.write, 1);
  posix_spawn_file_actions_adddup2(&actions, output.write, 2);
  posix_spawn_file_actions_adddup2(&actions, result.write, kResultFd);
  // Its own process group: a helper the driver forks (a crash handler, a cache daemon) inherits it,
  // so the deadline and the end of the child kill the whole group (kill_group).
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  const int rc = posix_spawn(&child->pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  close(result.write);
  close(output.write);
  if (rc != 0) {
    close(result.read);
    close(output.read);
    throw std::runtime_error(fmt::format("could not start {}: {}", args[0], std::strerror(rc)));
  }
  child->result_fd = result.read;
  child->output_fd = output.read;
  child->begun.assign(batch.size(), false);
  child->recorded.assign(batch.size(), false);
  child->batch = std::move(batch);
  child->started = child->case_started = Clock::now();
  return child;
}

// Kills and reaps every child still running when the run ends early (an exception).
struct ChildrenGuard {
  std::vector<std::unique_ptr<Child>>& children;
  ~ChildrenGuard() {
    for (auto& c : children) {
      kill_group(*c);
      if (c->pid > 0) waitpid(c->pid, nullptr, 0);
      close_fd(c->result_fd);
      close_fd(c->output_fd);
    }
  }
};

// Reads what is there; returns false at end of file.
bool drain(int fd, std::string& into) {
  char buffer[65536];
  for (;;) {
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n > 0) {
      into.append(buffer, size_t(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    return n < 0 && errno == EAGAIN;
  }
}

// Handles the complete lines of the result pipe. A line that is not the protocol's (a driver that
// writes into the descriptor, a half record) is the child's fault, never the run's: the child is
// killed, and the case it was running is a Crash that names the line (run_in_children).
void take_results(Child& c, const std::function<void(ChildOutcome&&)>& done) {
  size_t end;
  while (c.broken.empty() && (end = c.result_buffer.find('\n')) != std::string::npos) {
    const std::string line = c.result_buffer.substr(0, end);
    c.result_buffer.erase(0, end + 1);
    const auto tab1 = line.find('\t');
    const std::string kind = line.substr(0, tab1);
    const auto tab2 = tab1 == std::string::npos ? std::string::npos : line.find('\t', tab1 + 1);
    size_t i = c.batch.size();
    try {
      if (tab1 != std::string::npos)
        i = std::stoul(line.substr(tab1 + 1, tab2 == std::string::npos ? std::string::npos : tab2 - tab1 - 1));
    } catch (const std::exception&) {
      i = c.batch.size();
    }
    const bool well_formed =
        i < c.batch.size() && (kind == "begin" || (kind == "record" && tab2 != std::string::npos && c.current == i));
    if (!well_formed) {
      c.broken = "wrote an unexpected line on the result pipe: " + line.substr(0, 200);
      break;
    }
    if (kind == "begin") {
      c.begun[i] = true;
      c.current = i;
      c.case_started = Clock::now();
      continue;
    }
    ChildOutcome outcome;
    try {
      const nlohmann::json j = nlohmann::json::parse(line.substr(tab2 + 1));
      outcome.record = case_from_json(j, "(result pipe)", "$");
      outcome.duration_s = j.value("duration_s", 0.0);
    } catch (const std::exception& e) {
      c.broken = std::string("wrote a record that does not read (") + e.what() + "): " + line.substr(0, 200);
      break;
    }
    outcome.id = c.batch[i].id;
    outcome.record.duration_s = outcome.duration_s;
    c.recorded[i] = true;
    c.recorded_any = true;
    c.current.reset();
    done(std::move(outcome));
  }
  if (!c.broken.empty()) kill_group(c);
}

void trim_output(std::string& output) {
  if (output.size() > kOutputKept) output.erase(0, output.size() - kOutputKept);
}

}  // namespace

std::string last_lines(const std::string& text, size_t max_lines) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    const auto end = text.find('\n', start);
    std::string line = text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!line.empty()) lines.push_back(std::move(line));
    start = end == std::string::npos ? text.size() : end + 1;
  }
  std::string out;
  for (size_t i = lines.size() > max_lines ? lines.size() - max_lines : 0; i < lines.size(); ++i)
    out += "\n  | " + lines[i];
  return out;
}

std::vector<size_t> run_in_children(const ChildRunOptions& o, const std::vector<ChildCase>& cases,
                                    const std::atomic<int>& stop, const std::function<void(ChildOutcome&&)>& done) {
  std::deque<ChildCase> queue(cases.begin(), cases.end());
  std::vector<size_t> not_run;
  std::vector<std::unique_ptr<Child>> children;
  ChildrenGuard guard{children};
  const unsigned jobs = std::max(1u, o.jobs);
  const size_t batch_size = std::max<size_t>(1, o.batch_size);
  // A case's limit is the timeout; before its first case a child also has its start-up time.
  const auto limit = [&](const Child& c) {
    return c.current || c.recorded_any ? o.timeout_s : o.timeout_s + kStartupS;
  };

  while (!queue.empty() || !children.empty()) {
    const bool stopping = (stop.load() != 0);
    while (!stopping && !queue.empty() && children.size() < jobs) {
      std::vector<ChildCase> batch;
      while (!queue.empty() && batch.size() < batch_size) {
        batch.push_back(queue.front());
        queue.pop_front();
      }
      children.push_back(spawn(o, std::move(batch)));
    }
    if (stopping) {
      for (const ChildCase& c : queue) not_run.push_back(c.id);
      queue.clear();
      for (auto& c : children)
        if (!c->told_to_stop && c->pid > 0) {
          kill(c->pid, SIGTERM);  // the worker finishes its current case, then exits
          c->told_to_stop = true;
        }
    }

    // Wait for output, a child's end or the nearest deadline (at most 100 ms: `stop` is polled).
    std::vector<pollfd> fds;
    std::vector<std::pair<Child*, int*>> owners;
    const Clock::time_point now = Clock::now();
    double wait_s = 0.1;
    for (auto& c : children) {
      for (int* fd : {&c->result_fd, &c->output_fd})
        if (*fd >= 0) {
          fds.push_back({*fd, POLLIN, 0});
          owners.emplace_back(c.get(), fd);
        }
      if (!c->timed_out) wait_s = std::min(wait_s, limit(*c) - seconds(now - c->case_started));
    }
    const int timeout_ms = int(std::max(0.0, wait_s) * 1000) + 1;
    if (poll(fds.data(), nfds_t(fds.size()), timeout_ms) < 0 && errno != EINTR)
      throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
    for (size_t k = 0; k < fds.size(); ++k) {
      if (fds[k].revents == 0) continue;
      auto [child, fd] = owners[k];
      fcntl(*fd, F_SETFL, O_NONBLOCK);
      const bool more = drain(*fd, fd == &child->result_fd ? child->result_buffer : child->output);
      if (fd == &child->output_fd) trim_output(child->output);
      if (!more) close_fd(*fd);
      if (fd == &child->result_fd) take_results(*child, done);
    }

    // Deadlines: a case (or a child's start) past the timeout is killed, with its process group.
    // The deadline holds whatever the pipes do: closed by a child that hangs, or held open by a
    // helper after the child ended.
    for (auto& c : children)
      if (!c->timed_out && !c->exited && seconds(Clock::now() - c->case_started) > limit(*c)) {
        kill_group(*c);
        c->timed_out = true;
      }

    // Reap without blocking: the loop goes on polling `stop` and the deadlines. An ended child's
    // group is killed first, while its pid still names the group: helpers it left die with it.
    for (auto& c : children) {
      if (c->exited) continue;
      siginfo_t info{};
      if (waitid(P_PID, id_t(c->pid), &info, WEXITED | WNOHANG | WNOWAIT) != 0 || info.si_pid != c->pid) continue;
      kill_group(*c);
      while (waitpid(c->pid, &c->status, 0) < 0 && errno == EINTR) {
      }
      c->exited = true;
      c->pid = -1;
    }

    // Children that have ended: what they wrote is in the pipes (read now; a helper that still holds
    // them is not waited for, and dies with the group). Account for their cases.
    for (auto it = children.begin(); it != children.end();) {
      Child& c = **it;
      if (!c.exited) {
        ++it;
        continue;
      }
      for (int* fd : {&c.result_fd, &c.output_fd})
        if (*fd >= 0) {
          fcntl(*fd, F_SETFL, O_NONBLOCK);
          drain(*fd, fd == &c.result_fd ? c.result_buffer : c.output);
          close_fd(*fd);
        }
      trim_output(c.output);
      take_results(c, done);
      const int status = c.status;
      const double elapsed = seconds(Clock::now() - c.case_started);
      const std::string tail = last_lines(c.output, kOutputLines);
      const bool began_any = std::find(c.begun.begin(), c.begun.end(), true) != c.begun.end();
      // Bad input or no device, found before the child began any case, is the run's (exit 2, 3); once
      // it began a case, whatever ends it (a driver that calls exit(2)) costs that case alone.
      const bool run_problem = !c.timed_out && c.broken.empty() && !began_any && WIFEXITED(status);
      if (run_problem && WEXITSTATUS(status) == 2)
        throw InputError(o.report_dir, "", "a conformance child process failed:" + tail);
      if (run_problem && WEXITSTATUS(status) == 3)
        throw EnvironmentError("a conformance child process found no Vulkan device:" + tail);
      if (c.current) {
        ChildOutcome outcome;
        outcome.id = c.batch[*c.current].id;
        outcome.duration_s = elapsed;
        if (c.timed_out) {
          outcome.end = ChildEnd::Timeout;
          outcome.message = fmt::format("ran past --timeout {:g} s (killed after {:.1f} s); last output:{}",
                                        o.timeout_s, elapsed, tail.empty() ? " (none)" : tail);
        } else if (!c.broken.empty()) {
          outcome.end = ChildEnd::Crash;
          outcome.message = fmt::format("the case's process {} after {:.2f} s and was killed; last output:{}", c.broken,
                                        elapsed, tail.empty() ? " (none)" : tail);
        } else {
          outcome.end = ChildEnd::Crash;
          outcome.message = fmt::format("the case's process {} after {:.2f} s; last output:{}", describe_status(status),
                                        elapsed, tail.empty() ? " (none)" : tail);
        }
        c.recorded[*c.current] = true;
        done(std::move(outcome));
      }
      std::vector<ChildCase> left;
      for (size_t i = 0; i < c.batch.size(); ++i)
        if (!c.recorded[i]) left.push_back(c.batch[i]);
      if (!began_any && !left.empty() && !c.told_to_stop) {
        // It never began a case: its start failed (or hung). No retrying in a loop: Missing.
        for (const ChildCase& lost : left) {
          ChildOutcome outcome;
          outcome.id = lost.id;
          outcome.end = ChildEnd::Missing;
          outcome.message = fmt::format("no result: the case's process {} before beginning it{}; last output:{}",
                                        c.broken.empty() ? describe_status(status) : c.broken + " and was killed",
                                        c.timed_out ? fmt::format(" (killed after {:.0f} s)", elapsed) : "",
                                        tail.empty() ? " (none)" : tail);
          done(std::move(outcome));
        }
      } else if ((stop.load() != 0) || c.told_to_stop) {
        for (const ChildCase& lost : left) not_run.push_back(lost.id);
      } else {
        queue.insert(queue.begin(), left.begin(), left.end());  // to a new child, first in line
      }
      it = children.erase(it);
    }
  }
  // In the given order.
  std::vector<size_t> ordered;
  for (const ChildCase& c : cases)
    if (std::find(not_run.begin(), not_run.end(), c.id) != not_run.end()) ordered.push_back(c.id);
  return ordered;
}

}  // namespace rastercmp

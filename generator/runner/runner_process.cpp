// SPDX-License-Identifier: GPL-2.0-or-later
#include "runner/runner_process.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <stdexcept>
#include <thread>

namespace kanegen::runner {

RunnerProcess::RunnerProcess(const std::string& runner, const std::vector<std::string>& args)
    : program_(runner) {
  // A runner that dies must give an exception here, not SIGPIPE for kanegen.
  std::signal(SIGPIPE, SIG_IGN);
  int in[2], out[2];
  if (pipe(in) != 0) throw std::runtime_error("cannot create a pipe to " + runner);
  if (pipe(out) != 0) {
    close(in[0]);
    close(in[1]);
    throw std::runtime_error("cannot create a pipe to " + runner);
  }
  std::vector<char*> argv{const_cast<char*>(runner.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error("cannot start " + runner);
  if (pid_ == 0) {
    dup2(in[0], STDIN_FILENO);
    dup2(out[1], STDOUT_FILENO);
    close(in[0]);
    close(in[1]);
    close(out[0]);
    close(out[1]);
    execv(runner.c_str(), argv.data());
    std::fprintf(stderr, "error: cannot run %s\n", runner.c_str());
    _exit(127);
  }
  close(in[0]);
  close(out[1]);
  // Later children (another runner) must not hold this runner's input open.
  fcntl(in[1], F_SETFD, FD_CLOEXEC);
  fcntl(out[0], F_SETFD, FD_CLOEXEC);
  to_ = fdopen(in[1], "w");
  from_ = fdopen(out[0], "r");
  if (!to_ || !from_) throw std::runtime_error("cannot open the pipes to " + runner);
}

RunnerProcess::~RunnerProcess() {
  try {
    finish();
  } catch (...) {
  }
}

std::string RunnerProcess::read_line() {
  std::string line;
  char buf[65536];
  while (std::fgets(buf, sizeof buf, from_)) {
    line += buf;
    if (line.back() == '\n') {
      line.pop_back();
      return line;
    }
  }
  if (line.empty()) throw std::runtime_error(program_ + " stopped answering (see its messages above)");
  return line;
}

std::string RunnerProcess::exchange(const std::string& line) {
  if (std::fputs(line.c_str(), to_) < 0 || std::fputc('\n', to_) == EOF || std::fflush(to_) != 0)
    throw std::runtime_error(program_ + " stopped reading (see its messages above)");
  return read_line();
}

std::vector<std::string> RunnerProcess::exchange_all(const std::vector<std::string>& lines) {
  bool written = true;
  std::thread writer([&] {
    for (const std::string& line : lines)
      if (std::fputs(line.c_str(), to_) < 0 || std::fputc('\n', to_) == EOF) {
        written = false;
        break;
      }
    if (std::fflush(to_) != 0) written = false;
  });
  std::vector<std::string> answers;
  try {
    for (std::size_t i = 0; i < lines.size(); ++i) answers.push_back(read_line());
  } catch (...) {
    writer.join();  // the runner has gone, so the writer's next write fails
    throw;
  }
  writer.join();
  if (!written) throw std::runtime_error(program_ + " stopped reading (see its messages above)");
  return answers;
}

int RunnerProcess::finish() {
  if (pid_ < 0) return 0;
  if (to_) std::fclose(to_);
  if (from_) std::fclose(from_);
  to_ = from_ = nullptr;
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0) {
  }
  pid_ = -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

nlohmann::json runner_info(const std::string& runner) {
  RunnerProcess process(runner, {"info"});
  const std::string line = process.read_line();
  if (process.finish() != 0) throw std::runtime_error(runner + " info failed");
  return nlohmann::json::parse(line);
}

namespace {

nlohmann::json parse_answer(const std::string& answer) {
  nlohmann::json reply;
  try {
    reply = nlohmann::json::parse(answer);
  } catch (const nlohmann::json::exception&) {
    throw std::runtime_error("the runner's answer is not JSON: " + answer.substr(0, 200));
  }
  if (reply.contains("error"))
    throw std::runtime_error("the runner rejected a request: " + reply["error"].get<std::string>());
  return reply;
}

}  // namespace

nlohmann::json batch_request(RunnerProcess& process, const nlohmann::json& request) {
  return parse_answer(process.exchange(request.dump()));
}

std::vector<nlohmann::json> batch_requests(RunnerProcess& process,
                                           const std::vector<nlohmann::json>& requests) {
  std::vector<std::string> lines;
  for (const nlohmann::json& r : requests) lines.push_back(r.dump());
  std::vector<nlohmann::json> replies;
  for (const std::string& answer : process.exchange_all(lines)) replies.push_back(parse_answer(answer));
  return replies;
}

nlohmann::json call_kernels(RunnerProcess& process, nlohmann::json request,
                            const std::vector<std::string>& kernels) {
  request["kernels"] = kernels;
  return batch_request(process, request).at("kernels");
}

}  // namespace kanegen::runner

#pragma once
// A helper program fed through a pipe (ffmpeg for the MP4 of a run and the live video stream), started without a
// shell: an argument vector goes to posix_spawnp, so no path or URL can run a command or be read as an option.

#include <sys/types.h>

#include <string>
#include <vector>

namespace gb {

// Starts `args` (args[0] looked up on PATH) with `stdinFd` as its stdin, in a process group of its own (a Ctrl-C at
// the terminal reaches this process, which then closes the pipe properly, and not the child), with SIGPIPE, SIGINT
// and SIGTERM at their defaults (this process ignores SIGPIPE, and an ignored signal stays ignored across exec).
// Throws std::runtime_error with the reason when it cannot be started.
pid_t spawnWithStdin(const std::vector<std::string>& args, int stdinFd);

}  // namespace gb

// What a SIGINT, SIGTERM or SIGHUP removes before the process dies of it: the temporary file
// being written (encoder/io/output_file) and a staging folder of frames not yet moved into
// place (encoder/io/output_folder). The handler only makes async-signal-safe calls.
#pragma once
#include <string>

#include <signal.h>

namespace dcurve {

// Installs the handler (a signal the process ignores stays ignored). SIGKILL cannot be
// caught: a temporary may then remain.
void remove_temporary_on_signal();

// Blocks the cleanup signals while a temporary's name and its existence change together.
class SignalBlock {
 public:
  SignalBlock();
  ~SignalBlock();
  SignalBlock(const SignalBlock&) = delete;
  SignalBlock& operator=(const SignalBlock&) = delete;

 private:
  sigset_t old_;
};

// The file the handler removes (at most one; call inside a SignalBlock). False when the
// name is too long to register.
bool set_temporary_file(const std::string& path);
void clear_temporary_file();

// The folder the handler empties and removes (flat: files only; at most one; an empty path
// clears it). False when the name is too long to register.
bool set_temporary_folder(const std::string& path);

}  // namespace dcurve

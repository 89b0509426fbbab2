#pragma once
/// @brief An X display for VTK's off-screen rendering: the user's own if it answers and gives
/// VTK its OpenGL, else a private Xvfb that lives exactly as long as this object.
///
/// Debian's VTK 9.1 renders through GLX only (no OSMesa, no EGL), so even off-screen pictures
/// need an X server. On Xvfb, Mesa's llvmpipe (libgl1-mesa-dri, which libvtk9.1 already pulls
/// in) gives VTK the OpenGL 3.2+ core context it needs (4.5 with Mesa 22); no LIBGL_* setting is
/// needed. VTK crashes in its first render without such a context, so the constructor checks
/// for one (about 0.1 s) and the render functions rely on that.
///
/// Limitations, said plainly:
/// - The constructor sets DISPLAY for the whole process (setenv): create it before starting
///   threads that read the environment, and only one at a time.
/// - Every VTK render window must be destroyed before this object: Xlib exits the process when
///   its server goes away under an open connection.
/// - The server is also stopped if this process dies without unwinding (PR_SET_PDEATHSIG), which
///   Linux ties to the creating thread: create it on a thread that outlives it (the main one).

#include <string>
#include <sys/types.h>

namespace ligsim::render {

class OffscreenDisplay {
public:
  /// Uses $DISPLAY if it is set, its server accepts a connection and VTK gets OpenGL 3.2 there;
  /// otherwise starts `Xvfb -displayfd <fd> -nolisten tcp` with a 24-bit screen and points
  /// DISPLAY at it. Throws InputError if Xvfb is needed but not on PATH (the message says to
  /// install xvfb or to pass --no-images) or fails to start (with its last message), Error if
  /// VTK gets no OpenGL 3.2 on it.
  OffscreenDisplay();
  /// Stops the private Xvfb (SIGTERM, then SIGKILL after 5 s; always reaped) and restores
  /// DISPLAY as it was.
  ~OffscreenDisplay();
  OffscreenDisplay(const OffscreenDisplay&) = delete;
  OffscreenDisplay& operator=(const OffscreenDisplay&) = delete;

  /// True if this object started (and owns) an Xvfb server.
  bool started_server() const { return m_server_pid > 0; }
  /// The display in use, e.g. ":0" or ":99".
  std::string display() const { return m_display; }
  /// The process id of the private Xvfb; 0 if the user's display is used.
  pid_t server_pid() const { return m_server_pid; }

private:
  /// Starts Xvfb and sets m_display (not DISPLAY); `why` says why the user's display is not used.
  void start_xvfb(const std::string& why);
  void stop_xvfb();
  void restore_display() const;

  std::string m_display;
  pid_t m_server_pid = 0;
  bool m_had_display = false;     ///< DISPLAY was set before (restored in the destructor)
  std::string m_previous_display; ///< its value
};

} // namespace ligsim::render

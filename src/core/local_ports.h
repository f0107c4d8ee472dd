#pragma once
/// TCP ports on the loopback interface, for what rescuesim starts beside itself (a ROS master for
/// benches and tests, servers under test).

namespace rescuesim {

/// A TCP port nobody listens on right now on 127.0.0.1 (the kernel's pick for port 0), or -1.
/// Free when asked, not reserved: whoever binds it next gets it.
int free_local_port();

/// True when something accepts TCP connections on 127.0.0.1:port.
bool local_port_open(int port);

}  // namespace rescuesim

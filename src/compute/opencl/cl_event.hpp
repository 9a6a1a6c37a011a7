#pragma once
// A cl_event as Event, timed with the queue's profiling counters.
#include <string>

#include "compute/opencl/cl_handle.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::opencl {

class ClEvent final : public Event {
 public:
  ClEvent(EventHandle event, std::string device) : event_(std::move(event)), device_(std::move(device)) {}
  void wait() override;
  double elapsed_ms() override;
  std::optional<double> elapsed_since_ms(Event& earlier) override;

 private:
  EventHandle event_;
  std::string device_;
};

}  // namespace depthtrack::compute::opencl

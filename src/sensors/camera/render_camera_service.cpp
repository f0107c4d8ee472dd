#include "sensors/camera/render_camera_service.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <future>

#include "core/error.h"
#include "core/thread.h"
#include "sensors/camera/camera.h"

namespace rescuesim {

/// One camera frame on its way: what to render, and what came out.
struct RenderCameraService::Job {
  SensorInstance sensor;
  const SensorSpec* spec = nullptr;
  SimTime stamp, due;
  State state;                       // the snapshot it shows
  Rng rng{0, "frame"};               // drawn from the sensor's stream at sample time; the render thread draws from it
  Rng rng_at_sample{0, "frame"};     // the same stream untouched, to render the frame again after a restore
  std::uint64_t generation = 0;      // RenderCameraService::generation_ when queued
  std::vector<std::pair<TopicId, msg::Message>> out;
  std::vector<int> victims_seen;
  bool done = false;
  bool dropped = false;              // taken off the queue by a restore before it was rendered
};

RenderCameraService::RenderCameraService(const World& world, const CameraServiceOptions& options) : world_(world), options_(options) {
  thermal_robot_.assign(world.robots.size(), false);
  for (std::size_t r = 0; r < world.robots.size(); ++r) {
    for (const auto& s : world.robots[r].spec.sensors) {
      if (s.enabled && s.type == SensorSpec::Type::thermal_camera) thermal_robot_[r] = true;
    }
  }
  // the GL context belongs to the render thread: create it there and report how it went
  std::promise<std::string> ready;
  auto started = ready.get_future();
  thread_ = start_named_thread("render", [this, &ready] {
    std::unique_ptr<Renderer> renderer;
    try {
      renderer = Renderer::create_headless(options_.quality);
      renderer->load(build_render_scene(world_));
      ready.set_value(renderer->device());
    } catch (const std::exception& e) {
      ready.set_exception(std::current_exception());
      return;
    }
    RenderScene scene = build_render_scene(world_);
    SimTime shown{-1};
    std::uint64_t shown_generation = 0;
    for (;;) {
      std::shared_ptr<Job> job;
      {
        std::unique_lock lock(mutex_);
        work_.wait(lock, [this] { return stop_ || !queue_.empty(); });
        if (queue_.empty()) return;
        job = queue_.front();
        queue_.pop_front();
      }
      try {
        // cameras sampled at the same step share one scene update
        if (job->stamp != shown || job->generation != shown_generation) {
          shown_generation = job->generation;
          update_render_scene(scene, job->state);
          renderer->update(scene);
          shown = job->stamp;
        }
        const CameraView view = camera_view(world_, job->state, job->sensor.robot, *job->spec);
        const msg::Header header{job->stamp, job->sensor.frame_id};
        job->out.emplace_back(job->sensor.info_topic, camera_info(*job->spec, header));
        switch (job->spec->type) {
          case SensorSpec::Type::color_camera:
            job->out.emplace_back(job->sensor.topic, color_message(renderer->color(view), *job->spec, header, job->rng));
            break;
          case SensorSpec::Type::depth_camera: {
            msg::Image depth = depth_message(renderer->depth(view), *job->spec, header, job->rng);
            if (job->sensor.extra_topic != kNoTopic) job->out.emplace_back(job->sensor.extra_topic, depth_cloud(depth, *job->spec));
            job->out.emplace(job->out.begin() + 1, job->sensor.topic, std::move(depth));
            break;
          }
          case SensorSpec::Type::thermal_camera: {
            msg::Image mono16 = thermal_mono16(renderer->thermal(view, job->spec->camera.blur_sigma), *job->spec, header, job->rng);
            job->victims_seen = victims_in_thermal_image(world_, view, *job->spec, mono16, options_.victim_contrast);
            job->out.emplace_back(job->sensor.extra_topic, thermal_mono8(mono16, *job->spec));
            job->out.emplace(job->out.end() - 1, job->sensor.topic, std::move(mono16));
            break;
          }
          default: break;
        }
      } catch (const std::exception& e) {
        std::lock_guard lock(mutex_);
        error_ = e.what();
      }
      {
        std::lock_guard lock(mutex_);
        job->done = true;
      }
      done_.notify_all();
    }
  });
  try {
    device_ = started.get();
  } catch (...) {
    thread_.join();
    throw;
  }
}

RenderCameraService::~RenderCameraService() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  work_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool RenderCameraService::detects_victims(RobotIndex robot) const { return thermal_robot_[robot.slot()]; }

void RenderCameraService::sample(const World& world, const State& state, const SensorInstance& sensor, SensorSlot& slot) {
  auto job = std::make_shared<Job>();
  job->sensor = sensor;
  job->spec = &world.robot(sensor.robot).spec.sensors[static_cast<std::size_t>(sensor.index)];
  job->stamp = state.time;
  const SimTime latency = options_.latency < 0 ? sensor.period : SimTime::from_seconds(options_.latency);
  job->due = state.time + latency;
  job->state = state;
  // the frame's noise comes from a stream seeded by the sensor's own, advanced here
  job->rng = Rng(slot.rng.next_u64(), "frame");
  job->rng_at_sample = job->rng;
  {
    std::lock_guard lock(mutex_);
    job->generation = generation_;
    queue_.push_back(job);
    pending_.push_back(job);
  }
  work_.notify_one();
}

void RenderCameraService::deliver(const World& world, State& state, SimTime now,
                                  const std::function<void(TopicId, msg::Message)>& publish) {
  for (;;) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock lock(mutex_);
      if (pending_.empty() || pending_.front()->due > now) return;
      job = pending_.front();
      done_.wait(lock, [&] { return job->done; });
      pending_.pop_front();
      if (!error_.empty()) throw Error({"", 0, "camera " + job->spec->name}, "rendering failed: " + error_);
    }
    for (auto& [topic, m] : job->out) {
      if (topic == kNoTopic) continue;
      if (topic == job->sensor.topic) {
        const auto& img = std::get<msg::Image>(m);
        bool found = false;
        for (auto& f : last_) {
          if (f.robot == job->sensor.robot && f.sensor == job->spec->name) {
            f.image = img;
            found = true;
          }
        }
        if (!found) last_.push_back({job->sensor.robot, job->spec->name, img});
      }
      publish(topic, std::move(m));
    }
    for (int v : job->victims_seen) {
      const auto r = job->sensor.robot.slot();
      state.victims[static_cast<std::size_t>(v)].saw(r, world.robots.size(), world.robots[r].name, job->stamp);
    }
  }
}

std::vector<RenderCameraService::LastFrame> RenderCameraService::last_frames() const { return last_; }

const msg::Image* RenderCameraService::last_frame(RobotIndex robot, const std::string& sensor) const {
  for (const LastFrame& f : last_) {
    if (f.robot == robot && f.sensor == sensor) return &f.image;
  }
  return nullptr;
}

RenderCameraService::InFlight RenderCameraService::in_flight() const {
  std::lock_guard lock(mutex_);
  return InFlight{{pending_.begin(), pending_.end()}};
}

void RenderCameraService::restore(const InFlight& frames) {
  {
    std::unique_lock lock(mutex_);
    // what is still queued is dropped; the frame being rendered is waited for and thrown away
    for (auto& job : queue_) job->dropped = true;
    queue_.clear();
    done_.wait(lock, [this] {
      return std::all_of(pending_.begin(), pending_.end(), [](const auto& job) { return job->done || job->dropped; });
    });
    pending_.clear();
    ++generation_;
    // the saved frames go back to be rendered from their inputs
    for (const auto& saved : frames.frames) {
      auto job = std::make_shared<Job>();
      job->sensor = saved->sensor;
      job->spec = saved->spec;
      job->stamp = saved->stamp;
      job->due = saved->due;
      job->state = saved->state;
      job->rng = saved->rng_at_sample;
      job->rng_at_sample = saved->rng_at_sample;
      job->generation = generation_;
      queue_.push_back(job);
      pending_.push_back(job);
    }
  }
  work_.notify_one();
}

}  // namespace rescuesim

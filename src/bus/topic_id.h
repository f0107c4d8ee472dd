#pragma once
/// Topic ids, in a header of their own so that sensor code (SensorInstance, CameraService) can
/// name the Bus topics it publishes on without the Bus itself.

namespace rescuesim {

/// A topic's id: its index in Bus::topics(). A type of its own, so that a topic id and a
/// subscription handle cannot be mixed up (`bus.unsubscribe(topic)` does not compile).
enum class TopicId : int {};
/// No topic (Bus::find of an unknown name; a sensor without that output).
inline constexpr TopicId kNoTopic{-1};

}  // namespace rescuesim

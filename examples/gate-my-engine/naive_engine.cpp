#include "naive_engine.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace naive {
namespace {

Vec operator+(Vec p, Vec q) { return {p.x + q.x, p.y + q.y}; }
Vec operator-(Vec p, Vec q) { return {p.x - q.x, p.y - q.y}; }
Vec operator*(double s, Vec p) { return {s * p.x, s * p.y}; }
double dot(Vec p, Vec q) { return p.x * q.x + p.y * q.y; }

// The point of segment ab nearest to p.
Vec nearest_on_segment(Vec p, Vec a, Vec b) {
  const Vec ab = b - a;
  const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
  return a + t * ab;
}

}  // namespace

Engine::Engine(const pge::Scene& scene)
    : gravity_{scene.world.gravity.x, scene.world.gravity.y}, restitution_(scene.world.restitution) {
  for (const pge::BodyDesc& d : scene.bodies) {
    Body body{d.id, d.shape == pge::ShapeKind::Segment, {d.position.x, d.position.y},
              {d.velocity.x, d.velocity.y}, {}, {}, d.radius, d.mass};
    if (body.wall) {
      body.a = body.position + Vec{d.a.x, d.a.y};
      body.b = body.position + Vec{d.b.x, d.b.y};
    } else if (d.shape != pge::ShapeKind::Circle || d.fixed) {
      throw std::invalid_argument("naive engine: body \"" + d.id + "\" is neither a moving circle nor a fixed segment");
    }
    bodies_.push_back(body);
  }
}

std::vector<Contact> Engine::step(double dt) {
  for (Body& body : bodies_) {
    if (body.wall) continue;
    body.velocity = body.velocity + dt * gravity_;  // semi-implicit Euler: velocity first
    body.position = body.position + dt * body.velocity;
  }
  time_ += dt;
  std::vector<Contact> contacts;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies_.size(); ++j) {
      Vec normal;
      if (!touch(i, j, normal)) continue;
      bounce(i, j, normal);
      contacts.push_back({i, j});
    }
  }
  return contacts;
}

// Whether i and j overlap now (the only test: what happened inside the step is never looked at);
// `normal` is the unit direction from i towards j.
bool Engine::touch(std::size_t i, std::size_t j, Vec& normal) const {
  const Body& p = bodies_[i];
  const Body& q = bodies_[j];
  if (p.wall && q.wall) return false;
  Vec from, to;
  if (p.wall) {
    from = nearest_on_segment(q.position, p.a, p.b), to = q.position;
  } else if (q.wall) {
    from = p.position, to = nearest_on_segment(p.position, q.a, q.b);
  } else {
    from = p.position, to = q.position;
  }
  const Vec d = to - from;
  const double distance = std::sqrt(dot(d, d));
  if (distance >= p.radius + q.radius || distance == 0) return false;
  normal = (1 / distance) * d;
  return true;
}

// An impulse along the normal if the pair approaches; walls have infinite mass.
void Engine::bounce(std::size_t i, std::size_t j, Vec normal) {
  Body& p = bodies_[i];
  Body& q = bodies_[j];
  const double approach = dot(p.velocity - q.velocity, normal);
  if (approach <= 0) return;
  const double inv_p = p.wall ? 0 : 1 / p.mass;
  const double inv_q = q.wall ? 0 : 1 / q.mass;
  const double impulse = (1 + restitution_) * approach / (inv_p + inv_q);
  p.velocity = p.velocity - (impulse * inv_p) * normal;
  q.velocity = q.velocity + (impulse * inv_q) * normal;
}

}  // namespace naive

// Writes values[i] = i*i + offset (mod 2^32) for i < count: a pattern the host can check word
// for word, proving that GLSL -> SPIR-V -> pipeline -> dispatch -> readback all work.
#version 450

layout(local_size_x = 64) in;

layout(std430, set = 0, binding = 0) writeonly buffer Values {
  uint values[];
};

layout(push_constant) uniform Params {
  uint count;   // how many values to write; the last work group covers past the end
  uint offset;
} params;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= params.count) return;
  values[i] = i * i + params.offset;
}

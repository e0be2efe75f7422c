// Placeholder translation unit so the collision target exists before its first real sources land.
namespace stairplan {}

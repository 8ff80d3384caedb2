//! Wavefront OBJ reader (placeholder; being written).

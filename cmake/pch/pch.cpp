// The translation unit that carries a precompiled header (cmake/RescuesimPch.cmake); no code.

// The translation unit that builds testing_pch.h's precompiled header (tests/CMakeLists.txt).

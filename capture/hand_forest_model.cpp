// The trained hand forest (hand_forest.h) embedded as read-only bytes: HandForest::builtin() reads them. The
// model file's path comes from CMake (GB_HAND_FOREST_MODEL), which also rebuilds this file when the model changes.
#ifndef GB_HAND_FOREST_MODEL
#error "GB_HAND_FOREST_MODEL must name the model file"
#endif

__asm__(
    ".section .rodata\n"
    ".balign 16\n"
    ".global gb_hand_forest_model_begin\n"
    "gb_hand_forest_model_begin:\n"
    ".incbin \"" GB_HAND_FOREST_MODEL
    "\"\n"
    ".global gb_hand_forest_model_end\n"
    "gb_hand_forest_model_end:\n"
    ".previous\n");

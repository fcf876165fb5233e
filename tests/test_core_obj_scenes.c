/* SPDX-License-Identifier: Apache-2.0 */
/* test_core_obj_scenes.c - the OBJ loader on the real shared scenes, with the
 * counts of /work/shared/scenes/SOURCES.md. Skips when they are absent. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "formats/obj_load.h"

static void test_shared_scenes(void) {
    /* test_shared_scene answers in a static buffer: keep copies. */
    char sponza[4096], cornell[4096], bunny[4096];
    const char *found[3] = {test_shared_scene("sponza_dabrovic/sponza.obj"), NULL, NULL};
    if (found[0]) snprintf(sponza, sizeof sponza, "%s", found[0]);
    found[1] = test_shared_scene("cornell_box/CornellBox-Original.obj");
    if (found[1]) snprintf(cornell, sizeof cornell, "%s", found[1]);
    found[2] = test_shared_scene("stanford_bunny/stanford-bunny.obj");
    if (found[2]) snprintf(bunny, sizeof bunny, "%s", found[2]);
    if (!found[0] || !found[1] || !found[2]) {
        test_skip("the shared scenes (sponza, cornell box, bunny) are not present");
    }
    rt_obj_mesh m;
    rt_error err;
    CHECK(rt_obj_load(sponza, &m, &err) == RT_OK);
    CHECK_EQ_INT(m.triangle_count, 66454);
    CHECK(m.normals != NULL);
    CHECK(m.vertex_count >= 39999);
    rt_obj_free(&m);

    CHECK(rt_obj_load(cornell, &m, &err) == RT_OK);
    CHECK_EQ_INT(m.triangle_count, 36);
    CHECK_EQ_INT(m.vertex_count, 72);
    CHECK(m.normals == NULL);
    CHECK(m.material_count > 0 && m.tri_materials != NULL);
    if (m.tri_materials) {
        int all_named = 1;
        for (uint32_t t = 0; t < m.triangle_count; t++)
            all_named &= m.tri_materials[t] < m.material_count;
        CHECK(all_named);
        const rt_obj_material *left = &m.materials[m.tri_materials[0]];
        printf("cornell: %u materials, first triangle uses \"%s\"\n", m.material_count, left->name);
    }
    for (uint32_t i = 0; i < m.material_count; i++)
        if (strcmp(m.materials[i].name, "leftWall") == 0)
            CHECK(m.materials[i].kd[0] == 0.63f && m.materials[i].ns == 10.0f &&
                  m.materials[i].ni == 1.5f);
    rt_obj_free(&m);

    CHECK(rt_obj_load(bunny, &m, &err) == RT_OK);
    CHECK_EQ_INT(m.triangle_count, 69451);
    CHECK_EQ_INT(m.vertex_count, 35947);
    rt_obj_free(&m);
}

int main(void) {
    test_shared_scenes();
    return TEST_END();
}

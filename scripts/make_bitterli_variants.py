"""Writes <scene>-v23.pbrt beside five Bitterli scenes of the w3ntao/pbrt-minus-scenes copies,
whose files of 4 MiB and more are absent: each absent texture replaced by one present in the same
scene, absent meshes dropped, the absent sky a constant, and veach-ajar's bdpt (which pbrt_ext
lacks) made path for both renderers. docs/comparison.md (issue 23) compares them with pbrt-v4.

Usage: python3 scripts/make_bitterli_variants.py SCENES   (the checkout of w3ntao/pbrt-minus-scenes)
"""
import pathlib
import sys

root = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else sys.exit(__doc__)
subs = {
 'bathroom2': [('textures/WoodPanel.tga','textures/WoodFloor.tga'),
               ('Shape "plymesh"\n    "string filename" [ "models/Mesh005.ply" ]\n','')],
 'living-room': [('"string filename" "textures/Sky 19.pfm"','"rgb L" [0.8 0.9 1.0]'),
                 ('textures/wood5.tga','textures/picture8.tga'),('textures/wood.tga','textures/picture8.tga')],
 'staircase': [('textures/BrushedAluminium.tga','textures/Wood.tga'),('textures/Fabric.tga','textures/WoodPanel.tga'),
               ('textures/Painting2.tga','textures/Painting1.tga'),('textures/Painting3.tga','textures/Painting1.tga'),
               ('textures/WoodChair.tga','textures/Wood.tga')],
 'staircase2': [('textures/wood5.tga','textures/Tiles.tga')],
 'veach-ajar': [('textures/Good Textures_005844.tga','textures/cherry-wood-texture.tga'),
                ('textures/landscape-with-a-lake.tga','textures/cherry-wood-texture.tga')],
}
for scene, pairs in subs.items():
    src = root/scene/f'{scene}.pbrt'
    text = src.read_text()
    for a, b in pairs:
        assert a in text, (scene, a)
        text = text.replace(a, b)
    if scene == 'veach-ajar':
        text = text.replace('Integrator "bdpt"', 'Integrator "path"', 1)
    (root/scene/f'{scene}-v23.pbrt').write_text(text)
    print(root/scene/f'{scene}-v23.pbrt')

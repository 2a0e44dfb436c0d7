#!/usr/bin/env python3
"""Write a Mitsuba 3 dialect scene (the benchmark scenes') in Mitsuba 0.6's dialect, for
side-by-side timing against Mitsuba 0.6 (docs/performance.md, "Side by side with Mitsuba 0.6").

    python3 bench/to_mitsuba06.py bench/scenes/pool/scene.xml OUT.xml [--integrator 'XML']

Files the scene names (meshes, images) are looked up beside OUT.xml: copy them there.
Only what the benchmark scenes use is converted: the version, the snake_case parameter names
Mitsuba 0.6 spells in camelCase, points given as one "x, y, z" value, and the film's banner
(off). --integrator replaces the scene's integrator element (or adds one) with the given XML;
its `$name` parameters become `-Dname=value` on Mitsuba's command line. A sampler is added
when the sensor has none, with `$spp` and `$seed` parameters, and an independent sampler
gets a `$seed` parameter (for runs with different seeds).
"""
import argparse
import re
import sys

RENAMED = {
    "to_world": "toWorld", "max_depth": "maxDepth", "rr_depth": "rrDepth", "sample_count": "sampleCount",
    "int_ior": "intIOR", "ext_ior": "extIOR", "file_format": "fileFormat", "pixel_format": "pixelFormat",
    "flip_normals": "flipNormals", "face_normals": "faceNormals", "focus_distance": "focusDistance",
    "aperture_radius": "apertureRadius", "specular_reflectance": "specularReflectance",
    "diffuse_reflectance": "diffuseReflectance", "specular_transmittance": "specularTransmittance",
}


def convert(text, integrator):
    text = re.sub(r'<scene version="[^"]*"', '<scene version="0.6.0"', text)
    for new, old in ((v, k) for k, v in RENAMED.items()):
        text = text.replace(f'name="{old}"', f'name="{new}"')
    text = re.sub(r'<point name="(\w+)" value="([^"]+)"\s*/>',
                  lambda m: '<point name="%s" x="%s" y="%s" z="%s"/>' % ((m.group(1),) + tuple(v.strip() for v in m.group(2).split(","))),
                  text)
    text = re.sub(r"(<film type=\"hdrfilm\">)", r'\1<boolean name="banner" value="false"/>', text)
    if "<sampler" in text and 'name="seed"' not in text:
        text = re.sub(r"(<sampler type=\"independent\">)", '\\1<integer name="seed" value="$seed"/>', text, count=1)
    if "<sampler" not in text:
        text = re.sub(r"(<film type=)", '<sampler type="independent"><integer name="sampleCount" value="$spp"/>'
                      '<integer name="seed" value="$seed"/></sampler>\n    \\1', text, count=1)
    if integrator:
        if re.search(r"<integrator\b", text):
            text = re.sub(r"<integrator\b.*?</integrator>|<integrator\b[^>]*/>", lambda m: integrator, text, count=1, flags=re.S)
        else:
            text = re.sub(r"(<scene version=\"0.6.0\">)", "\\1\n  " + integrator.replace("\\", "\\\\"), text, count=1)
    for name, value in (("spp", "16"), ("seed", "0")):
        if f"${name}" in text and f'<default name="{name}"' not in text:
            text = text.replace('<scene version="0.6.0">', f'<scene version="0.6.0">\n  <default name="{name}" value="{value}"/>', 1)
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene")
    parser.add_argument("out")
    parser.add_argument("--integrator", help="XML of the integrator element to use")
    args = parser.parse_args()
    try:
        with open(args.scene) as f:
            text = f.read()
    except OSError as e:
        sys.exit(f"{args.scene}: {e.strerror}")
    with open(args.out, "w") as f:
        f.write(convert(text, args.integrator))


if __name__ == "__main__":
    main()

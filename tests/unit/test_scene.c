/* test_scene.c: the scene parser: a full scene, defaults, and errors with exact file:line:col positions. */
#include "unit.h"
#include "scene.h"

#include <math.h>

static int fails(const char *text, const char *want)
{
	scene_t *s;
	char err[512];
	int rc = scene_parse(text, "t.scene", &s, err, sizeof err);
	if (rc == 0) {
		scene_free(s);
		printf("# parsed, wanted error '%s'\n", want);
		return 0;
	}
	if (strncmp(err, want, strlen(want)))
		printf("# got '%s'\n# want '%s'\n", err, want);
	return strncmp(err, want, strlen(want)) == 0;
}

static const char *good =
	"# a comment line\n"
	"view\n"
	"  eye 0 2 -6   # trailing comment\n"
	"  look-at 0 0 0\n"
	"  up 0 1 0\n"
	"  fov 50\n"
	"  size 64 48\n"
	"  projection stereoscopic\n"
	"  stereo-layout pages\n"
	"end\n"
	"\n"
	"background 0 0 0.2\n"
	"light point 0 8 -6 colour 1 0.9 0.8 shadows\n"
	"light directional 1 1 -1\n"
	"shape ball\n"
	"  point 0 0 0\n"
	"  c 1\n"
	"end\n"
	"object thing\n"
	"  points 1 0 0  -1 0 0 weight 0.5\n"
	"  segment 0 0 0 0 1 0\n"
	"  distance-to ball weight 0.25\n"
	"  c 2 + 0.1*sin(3*x)\n"
	"  rotate y 30\n"
	"  scale 2\n"
	"  translate 0 1 0\n"
	"  colour 0.2 0.4 0.6\n"
	"  shading gouraud\n"
	"  shininess 12\n"
	"end\n"
	"render raytrace\n"
	"  supersample 3\n"
	"end\n"
	"render octree\n"
	"  depth 5\n"
	"  test cubical\n"
	"end\n"
	"render voronoi\n"
	"  point 0 0 weight 0.5 colour 1 0 0\n"
	"  segment -1 -1 1 -1\n"
	"end\n";

int main(void)
{
	scene_t *s;
	char err[512];
	int rc = scene_parse(good, "t.scene", &s, err, sizeof err);
	CHECK(rc == 0, "a complete scene parses (%s)", rc ? err : "ok");
	if (rc == 0) {
		CHECK(s->cam.nxpix == 64 && s->cam.nypix == 48 && s->cam.fov == 50, "view size and fov");
		CHECK(s->stereo == SCENE_STEREO_PAGES, "stereo layout pages");
		CHECK(s->nlights == 2 && s->lights[0].shadows && !s->lights[1].shadows && s->lights[1].directional, "two lights");
		CHECK(s->nobjs == 2 && !s->objs[0].drawn && s->objs[1].drawn, "a shape (not drawn) and an object");
		const scene_obj_t *o = &s->objs[1];
		CHECK(o->shape->nel == 3 && o->shape->el[0].w == 0.5 && o->shape->el[2].kind == MODEL_SHAPE, "elements and weights");
		CHECK(o->shape->c.kind == MODEL_C_EXPR, "expression parameter");
		CHECK(o->mat.shading == RT_GOURAUD && o->mat.shininess == 12 && o->mat.colour[2] == 0.6, "material");
		CHECK(s->nrenders == 3 && s->renders[0].supersample == 3 && s->renders[1].test == SCENE_CUBICAL
		      && s->renders[2].nnuclei == 2, "render blocks");
		CHECK(o->shape->has_lip && fabs(o->shape->lip - ((0.5 + 1 + 0.1 * 3) * 0.5 + 0.25)) < 1e-9,
		      "L = (sum |w| of setup elements + G_c) / scale + shape weight (%g)", o->shape->lip);
		scene_free(s);
	}
	CHECK(fails("", "t.scene:1:1: expected an 'object' block or a 'render' block: the scene is empty"), "an empty scene is an error");
	CHECK(fails("# only a comment\n\n", "t.scene:1:1: expected an 'object' block or a 'render' block"), "a scene of comments is empty");
	CHECK(fails("shape s\n  point 0 0 0\n  c 1\nend\n", "t.scene:1:1: expected an 'object' block or a 'render' block: the scene defines only 'shape' blocks"), "shapes alone draw nothing");
	CHECK(fails("object a\n  point 0 0 0\n  c 1\n  c 2\nend\n", "t.scene:4:3: expected one 'c' line per shape: 'a' has its defining parameter from line 3 already"), "c given twice");
	CHECK(fails("object a\n  point 0 0 0 weight 0\n  c 1\nend\n", "t.scene:1:1: expected a non-zero weight: every element has weight 0"), "all-zero weights: not blamed on negative weights");
	CHECK(fails("object a\n  point 0 0 0 weight 0\n  c x\nend\n", "t.scene:1:1: expected a 'bound' box: the shape is unbounded (the weights of its finite elements are all 0)"), "zero weights, varying c: the reason");
	CHECK(fails("shape b\n  point 0 0 0\n  c 1\nend\nobject a\n  distance-to b\n  c 1\nend\n", "t.scene:5:1: expected a 'bound' box: the shape is unbounded (its elements are only distance-to"), "distance-to alone: says a bound is needed");
	CHECK(fails("object a\n  point 0 0 -1 weight -1\n  point 0 0 1\n  c 1\nend\n", "t.scene:1:1: expected a 'bound' box: the shape is unbounded (the weights of its finite elements sum to 0 or less"), "negative weights named as such");
	CHECK(fails("object a\n  point 0 0 0\n  c \033[2J\nend\n", "t.scene:3:5: expected a number, x, y, z, pi, e, a function or '(', found '\\x1b[2J'"), "control bytes escaped in the message");

	CHECK(fails("view\n  eye 0 0\nend\n", "t.scene:2:10: expected an eye coordinate (a finite number), found the end of the line"), "missing coordinate");
	CHECK(fails("objekt a\n", "t.scene:1:1: expected view, background, light, shape, object or render, found 'objekt'"), "unknown statement");
	CHECK(fails("object a\n  point 0 0 0\n  c 1 +\nend\n", "t.scene:3:8: expected a number"), "expression error column");
	CHECK(fails("object a\n  point 0 nan 0\n  c 1\nend\n", "t.scene:2:11: expected a coordinate (a finite number), found 'nan'"), "NaN coordinate");
	CHECK(fails("object a\n  point 0 0 0\n  distance-to b\nend\n", "t.scene:3:15: expected the name of a shape or object defined above, found 'b'"), "unknown name");
	CHECK(fails("object a\n  plane 0 0 0 0 1 0\n  c 1\nend\n", "t.scene:1:1: expected a 'bound' box: the shape is unbounded"), "unbounded shape needs a box");
	CHECK(fails("object a\n  point 0 0 0\n  c 1\n", "t.scene:4:1: expected 'end' closing the shape"), "missing end");
	CHECK(fails("view\n  eye 0 0 0\n  look-at 0 0 0\nend\n", "t.scene:1:1: expected an eye position different from the look-at point"), "degenerate view");
	CHECK(fails("light point 0 1 0 shadow\n", "t.scene:1:19: expected 'colour', 'shadows' or the end of the line, found 'shadow'"), "misspelt option");
	CHECK(fails("render raytrace\n  supersample 2.5\nend\n", "t.scene:2:1: expected supersample N: a whole number from 0 to 8"), "bad supersample");
	CHECK(fails("object a\n  point 0 0 0\n  c 1\n  colour 2 0 0\nend\n", "t.scene:4:1: expected colour components between 0 and 1"), "colour out of range");
	CHECK(fails("object a\n  point 0 0 0\n  scale 0\nend\n", "t.scene:3:3: expected non-zero scale factors"), "zero scale");
	CHECK(fails("object a\n  point 0 0 0 weight\nend\n", "t.scene:2:21: expected a weight (a finite number)"), "weight without value");
	CHECK(fails("object a\n  point 0 0 0\nend\nobject a\n", "t.scene:4:8: expected a name not used before, found 'a'"), "duplicate name");

	/* a degenerate model parses with a warning */
	rc = scene_parse("object a\n  point 1 0 0\n  point -1 0 0\n  c 1\nend\n", "t.scene", &s, err, sizeof err);
	CHECK(rc == 0 && s->nwarnings == 1 && strstr(s->warnings[0], "t.scene:1:1: warning: 'a': the shape is empty"), "c below the minimum: a warning");
	scene_free(s);
	/* c through X Y Z: c from a point of the surface, after the elements and transforms */
	rc = scene_parse("object a\n  point 0 0 0\n  point 1 0 0 weight 2\n  c through 3 0 0\n  translate 1 0 0\nend\n", "t.scene", &s, err, sizeof err);
	CHECK(rc == 0 && s->objs[0].shape->c.kind == MODEL_C_CONST && fabs(s->objs[0].shape->c.c0 - 4) < 1e-12
	      && fabs(model_eval(s->objs[0].shape, (double[]){3, 0, 0})) < 1e-12, "c through: c = 2 + 2*1 = %g, f = 0 at the point", rc == 0 ? s->objs[0].shape->c.c0 : -1);
	if (rc == 0)
		scene_free(s);
	CHECK(fails("object a\n  point 0 0 0\n  c through 1 0\nend\n", "t.scene:3:16: expected a point X Y Z on the surface (a finite number), found the end of the line"), "c through needs three numbers");
	/* a contour map of the same f (c 0, as the doc advises) is no reason to warn */
	rc = scene_parse("object a\n  point 1 0 0\n  point -1 0 0\n  c 0\nend\nrender contour\nend\n", "t.scene", &s, err, sizeof err);
	CHECK(rc == 0 && s->nwarnings == 0, "contour map of a shape with c 0: no 'empty' warning (%zu)", rc == 0 ? s->nwarnings : 99);
	scene_free(s);
	return UNIT_DONE();
}

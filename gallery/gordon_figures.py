"""Gordon's test surface in the settings of the paper's Figs. 7-14.

w = 3 sin(u cos v) on [-5, 5]^2 at 480x477 pixels, as in the paper's Table 1: the
floating horizon line drawing, intensity interpolation (iis, Gouraud), normal
interpolation (nis, per-pixel lighting) and a bird's-eye perspective, all with the
paper's reference shading (Lambert, light at the eye).
"""
import floatcol as fc

expr = "3*sin(u*cos(v))"
common = dict(u=(-5, 5), v=(-5, 5), size=(480, 477), elev=30, azim=20)

fc.render(expr, method="horizon", **common).save("line_drawing.png")
fc.render(expr, shading="lambert", interpolation="intensity", **common).save("iis.png")
fc.render(expr, shading="lambert", interpolation="normal", **common).save("nis.png")
fc.render(expr, shading="lambert", projection="perspective",
          **dict(common, elev=55)).save("birds_eye.png")

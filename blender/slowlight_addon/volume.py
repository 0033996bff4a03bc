# Blender volume shaders -> slowlight's homogeneous medium (sigma_s, sigma_a per Blender unit, g).
# Follows Cycles' closures: Volume Scatter adds sigma_s = density x colour; Volume Absorption adds
# sigma_a = density x (1 - colour); Principled Volume adds sigma_s = density x colour and
# sigma_a = density x max(1 - colour, 0) x max(1 - sqrt(absorption colour), 0); Add Shader sums,
# Mix Shader blends by its factor (coefficients are linear in closures). g is the scattering-
# weighted mean of the Henyey-Greenstein anisotropies. Whatever else is there is reported.
import math


class Medium:
    def __init__(self):
        self.sigma_s = [0.0, 0.0, 0.0]
        self.sigma_a = [0.0, 0.0, 0.0]
        self.g_weighted = 0.0  # sum of g x mean(sigma_s)
        self.gs = []

    def add(self, other, w):
        for i in range(3):
            self.sigma_s[i] += w * other.sigma_s[i]
            self.sigma_a[i] += w * other.sigma_a[i]
        self.g_weighted += w * other.g_weighted
        self.gs += other.gs

    @property
    def g(self):
        s = sum(self.sigma_s) / 3
        return self.g_weighted / s if s > 0 else 0.0

    def empty(self):
        return max(self.sigma_s + self.sigma_a) <= 0


def _value(node, name, where, warnings):
    sock = node.inputs[name]
    if sock.is_linked:
        warnings.append("%s: %s's %s is driven by a node link; its unlinked value is used "
                        "(slowlight's medium is homogeneous)" % (where, node.name, name))
    v = sock.default_value
    try:
        return [float(v[0]), float(v[1]), float(v[2])]
    except TypeError:
        return float(v)


def _scatter(m, colour, density, g):
    s = [max(c, 0.0) * density for c in colour]
    for i in range(3):
        m.sigma_s[i] += s[i]
    m.g_weighted += g * sum(s) / 3
    m.gs.append(g)


def from_socket(socket, where, warnings):
    """The medium a Volume socket receives (None when nothing is linked)."""
    if not socket.is_linked:
        return None
    link = socket.links[0]
    if link.from_node.bl_idname == 'NodeReroute':
        return from_socket(link.from_node.inputs[0], where, warnings)
    return _from_node(link.from_node, where, warnings)


def _from_node(node, where, warnings):
    m = Medium()
    kind = node.bl_idname
    if kind == 'ShaderNodeVolumeScatter':
        phase = getattr(node, "phase", 'HENYEY_GREENSTEIN')  # a choice since Blender 4.3
        if phase != 'HENYEY_GREENSTEIN':
            warnings.append("%s: %s's phase function %s is drawn as Henyey-Greenstein with its Anisotropy"
                            % (where, node.name, phase))
        density = max(_value(node, "Density", where, warnings), 0.0)
        _scatter(m, _value(node, "Color", where, warnings), density,
                 _value(node, "Anisotropy", where, warnings))
    elif kind == 'ShaderNodeVolumeAbsorption':
        density = max(_value(node, "Density", where, warnings), 0.0)
        m.sigma_a = [max(1.0 - c, 0.0) * density for c in _value(node, "Color", where, warnings)]
    elif kind == 'ShaderNodeVolumePrincipled':
        density = max(_value(node, "Density", where, warnings), 0.0)
        colour = _value(node, "Color", where, warnings)
        absorption = _value(node, "Absorption Color", where, warnings)
        _scatter(m, colour, density, _value(node, "Anisotropy", where, warnings))
        m.sigma_a = [max(1.0 - c, 0.0) * max(1.0 - math.sqrt(max(a, 0.0)), 0.0) * density
                     for c, a in zip(colour, absorption)]
        if _value(node, "Emission Strength", where, warnings) > 0 or \
                _value(node, "Blackbody Intensity", where, warnings) > 0:
            warnings.append("%s: %s emits light; a medium's emission is not carried" % (where, node.name))
    elif kind == 'ShaderNodeAddShader':
        for sock in node.inputs:
            part = from_socket(sock, where, warnings)
            if part:
                m.add(part, 1.0)
    elif kind == 'ShaderNodeMixShader':
        fac = min(max(_value(node, "Fac", where, warnings), 0.0), 1.0)
        for sock, w in ((node.inputs[1], 1.0 - fac), (node.inputs[2], fac)):
            part = from_socket(sock, where, warnings)
            if part:
                m.add(part, w)
    else:
        warnings.append("%s: the volume node %s (%s) is not carried" % (where, node.name, kind))
        return None
    if len(set(round(g, 6) for g in m.gs)) > 1:
        warnings.append("%s: volumes with different anisotropies %s are merged into one g = %.3f"
                        % (where, sorted(set(m.gs)), m.g))
        m.gs = [m.g]
    return m

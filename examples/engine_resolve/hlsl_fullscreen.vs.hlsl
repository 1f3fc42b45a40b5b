// fullscreen.vert in HLSL: one triangle that covers the screen, from the vertex index alone.
float4 main(uint vertex : SV_VertexID) : SV_Position
{
    const float2 corner = float2((vertex << 1) & 2, vertex & 2);
    return float4(corner * 2.0 - 1.0, 0.0, 1.0);
}

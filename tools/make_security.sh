#!/bin/sh
# DDS Security material for the uavmot chain: a CA, one certificate per node, governance and
# permissions signed by the CA, and one QoS profiles file per node whose `local` and `udp`
# participant profiles turn on PKI-DH authentication, AES-GCM-GMAC encryption and access control.
#
#   tools/make_security.sh OUT_DIR [QOS_XML]
#   uavmot launch bringup/ground.yaml ... --set qos_dir=OUT_DIR     # the one switch
#   uavmot launch bringup/air.yaml ...    --set qos_dir=OUT_DIR
#
#   uavmot launch bringup/local.yaml ...  --set qos_dir=OUT_DIR     # one host, the same material
#   UAVMOT_QOS_PROFILES=OUT_DIR/status.xml uavmot status
#
# Access control: only air nodes (source, motion, segmentation) may publish frames and motion
# estimates, only tracking may publish tracks and its state, only the air's downlink may publish
# what crosses the link (uavmot/downlink/*). Health: each node may publish uavmot/health only in
# the partition named after itself (src: components/dds/include/uavmot/dds/health_partitions.hpp),
# so no node can report as another; the readers that act on health (launch: the watchdog;
# status; downlink: passes the air's reports on) and the viewers (view, record, foxglove) may read it all.
# Fast DDS needs certificate paths as file:// + an absolute path.
set -eu

if [ $# -lt 1 ]; then
  echo "usage: $0 OUT_DIR [QOS_XML]" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
qos_xml=${2:-$here/../bringup/qos/uavmot_qos.xml}
[ -f "$qos_xml" ] || { echo "$0: QoS profiles file '$qos_xml' not found" >&2; exit 1; }
mkdir -p "$1"
out=$(cd "$1" && pwd)
nodes="source motion segmentation tracking downlink sink view record foxglove launch status"
days=3650

cd "$out"
openssl ecparam -name prime256v1 -genkey -noout -out ca.key 2>/dev/null
openssl req -x509 -new -key ca.key -sha256 -days $days -subj "/C=DE/O=uavmot/CN=uavmot CA" -out ca.pem 2>/dev/null

for node in $nodes; do
  openssl ecparam -name prime256v1 -genkey -noout -out "$node.key" 2>/dev/null
  openssl req -new -key "$node.key" -subj "/C=DE/O=uavmot/CN=$node" -out "$node.csr" 2>/dev/null
  openssl x509 -req -in "$node.csr" -CA ca.pem -CAkey ca.key -CAcreateserial -sha256 -days $days -out "$node.pem" 2>/dev/null
  rm -f "$node.csr"
done

cat > governance.xml <<'EOF'
<?xml version="1.0" encoding="UTF-8"?>
<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
  <domain_access_rules>
    <domain_rule>
      <domains><id_range><min>0</min><max>232</max></id_range></domains>
      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>
      <enable_join_access_control>true</enable_join_access_control>
      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>
      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>
      <rtps_protection_kind>NONE</rtps_protection_kind>
      <topic_access_rules>
        <topic_rule>
          <topic_expression>*</topic_expression>
          <enable_discovery_protection>true</enable_discovery_protection>
          <enable_liveliness_protection>true</enable_liveliness_protection>
          <enable_read_access_control>true</enable_read_access_control>
          <enable_write_access_control>true</enable_write_access_control>
          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>
          <data_protection_kind>ENCRYPT</data_protection_kind>
        </topic_rule>
      </topic_access_rules>
    </domain_rule>
  </domain_access_rules>
</dds>
EOF

# publish / subscribe topics per node
topics() {  # "topic ..." [partition]: one <publish>/<subscribe> criterion's body
  printf '<topics>'
  for t in $1; do printf '<topic>%s</topic>' "$t"; done
  printf '</topics>'
  [ -z "${2:-}" ] || printf '<partitions><partition>%s</partition></partitions>' "$2"
}
# name "published topics" "subscribed topics" [reads_health]: the node publishes health in its
# own partition only; with reads_health=yes it reads every partition of it ("*").
grant() {
  printf '    <grant name="%s">\n      <subject_name>CN=%s, O=uavmot, C=DE</subject_name>\n' "$1" "$1"
  printf '      <validity><not_before>2020-01-01T00:00:00</not_before><not_after>2120-01-01T00:00:00</not_after></validity>\n'
  printf '      <allow_rule>\n        <domains><id_range><min>0</min><max>232</max></id_range></domains>\n'
  [ -z "$2" ] || printf '        <publish>%s</publish>\n' "$(topics "$2")"
  printf '        <publish>%s</publish>\n' "$(topics uavmot/health "$1")"
  [ -z "$3" ] || printf '        <subscribe>%s</subscribe>\n' "$(topics "$3")"
  [ "${4:-}" != yes ] || printf '        <subscribe>%s</subscribe>\n' "$(topics uavmot/health '*')"
  printf '      </allow_rule>\n      <default>DENY</default>\n    </grant>\n'
}
chain="uavmot/frames uavmot/motion uavmot/segmentation uavmot/tracks"
{
  printf '<?xml version="1.0" encoding="UTF-8"?>\n<dds xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">\n  <permissions>\n'
  grant source "uavmot/frames" ""
  grant motion "uavmot/motion" "uavmot/frames"
  grant segmentation "uavmot/segmentation" "uavmot/frames uavmot/motion"
  grant tracking "uavmot/tracks uavmot/tracker_state" "uavmot/motion uavmot/segmentation"
  grant downlink "uavmot/downlink/results uavmot/downlink/preview" "$chain" yes
  grant sink "" "uavmot/motion uavmot/segmentation uavmot/tracks uavmot/downlink/results uavmot/downlink/preview"
  grant view "" "$chain" yes
  grant record "" "$chain uavmot/downlink/results uavmot/downlink/preview" yes
  grant foxglove "" "$chain uavmot/downlink/results uavmot/downlink/preview" yes
  grant launch "" "" yes
  grant status "" "" yes
  printf '  </permissions>\n</dds>\n'
} > permissions.xml

for doc in governance permissions; do
  openssl smime -sign -in "$doc.xml" -text -out "$doc.smime" -signer ca.pem -inkey ca.key
done

# Per node: the chain's QoS file with security properties in every participant profile.
for node in $nodes; do
  props="<propertiesPolicy><properties>\
<property><name>dds.sec.auth.plugin</name><value>builtin.PKI-DH</value></property>\
<property><name>dds.sec.auth.builtin.PKI-DH.identity_ca</name><value>file://$out/ca.pem</value></property>\
<property><name>dds.sec.auth.builtin.PKI-DH.identity_certificate</name><value>file://$out/$node.pem</value></property>\
<property><name>dds.sec.auth.builtin.PKI-DH.private_key</name><value>file://$out/$node.key</value></property>\
<property><name>dds.sec.crypto.plugin</name><value>builtin.AES-GCM-GMAC</value></property>\
<property><name>dds.sec.access.plugin</name><value>builtin.Access-Permissions</value></property>\
<property><name>dds.sec.access.builtin.Access-Permissions.permissions_ca</name><value>file://$out/ca.pem</value></property>\
<property><name>dds.sec.access.builtin.Access-Permissions.governance</name><value>file://$out/governance.smime</value></property>\
<property><name>dds.sec.access.builtin.Access-Permissions.permissions</name><value>file://$out/permissions.smime</value></property>\
</properties></propertiesPolicy>"
  sed "s|<rtps>|<rtps>$props|" "$qos_xml" > "$out/$node.xml"
done
chmod 600 ./*.key
echo "security material for: $nodes in $out"

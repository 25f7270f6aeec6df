// The Vulkan stepper's self-collision search (kernels/contacts/contact_*.comp): the contacts findContacts (collision.h)
// finds, found on the device and kept there for the sweeps.
#include <bit>
#include <cstdio>

#include "host/vulkan_stepper_impl.h"

namespace gb {

namespace {

// The device contact search's buckets for n particles: twice as many as particles, a power of two, as the CPU's
// table has for a film whose cells are fewer than its particles.
uint32_t contactBucketsFor(size_t particles) {
  uint32_t buckets = 64;
  while (buckets < 2 * particles) buckets *= 2;
  return buckets;
}

}  // namespace

void VulkanStepper::Impl::writeContacts(const Topology& t) {
  deviceListEntries = 0;  // replaced by this one
  ensureContactRoom(partnerEntriesOf(t.contacts), 0);
  writeVector(buffer(GB_BINDING_CONTACTS), t.contacts);
}

void VulkanStepper::Impl::ensureContactRoom(size_t entries, size_t previousUints) {
  if (entries > contactEntryCapacity)
    contactEntryCapacity = static_cast<uint32_t>(std::max<size_t>(entries, 2 * size_t{contactEntryCapacity}));
  contactBuckets = contactBucketsFor(particles);
  const size_t listUints = gpu::contactSearchAt(particles, contactEntryCapacity);  // what a device copy copies
  contactPreviousCapacity = std::max({contactPreviousCapacity, previousUints, listUints});
  contactRecord.rowCapacity = contactRowCapacity;
  contactRecord.entryCapacity = contactEntryCapacity;
  const size_t bytes = contactBufferUints() * sizeof(uint32_t);
  if (bytes <= buffer(GB_BINDING_CONTACTS).size()) return;
  DeviceBuffer grown(*ctx, bytes);
  copyContactUints(buffer(GB_BINDING_CONTACTS), 0, grown, 0, deviceListEntries);  // the device's list stays
  buffer(GB_BINDING_CONTACTS) = std::move(grown);
  writeDescriptorSets();
}

void VulkanStepper::Impl::copyContactUints(const DeviceBuffer& from, size_t fromUint, const DeviceBuffer& to,
                                           size_t toUint, size_t uints) {
  copyOnDevice(from, fromUint * sizeof(uint32_t), to, toUint * sizeof(uint32_t), uints * sizeof(uint32_t));
}

void VulkanStepper::Impl::recordContactScan(const vk::raii::CommandBuffer& cb, uint32_t count, uint32_t flags) {
  const uint32_t header = contactHeader();
  dispatchGroups(cb, Kernel::ContactScanBlocks, ceilDiv(count, workgroup * GB_SCAN_RUN), count, 0, flags, header);
  computeToComputeBarrier(cb);  // every block's sum is written before they are scanned
  dispatchGroups(cb, Kernel::ContactScanTotals, 1, count, 0, flags, header);  // one workgroup over the sums
  computeToComputeBarrier(cb);  // the sums are scanned before any block adds its own
  dispatch(cb, Kernel::ContactScanAdd, count, 0, flags, header);
  computeToComputeBarrier(cb);  // the scan is done before anyone reads it
}

std::array<uint32_t, GB_CONTACT_HEADER> VulkanStepper::Impl::contactSearchHeader(float frameTime, float slack,
                                                                                 uint32_t previousParticles) const {
  std::array<uint32_t, GB_CONTACT_HEADER> h{};
  h[GB_CONTACT_PREVIOUS_PARTICLES] = previousParticles;
  h[GB_CONTACT_ROW_CAPACITY] = contactRowCapacity;
  h[GB_CONTACT_ENTRY_CAPACITY] = contactEntryCapacity;
  h[GB_CONTACT_BUCKETS] = contactBuckets;
  h[GB_CONTACT_FRAME_TIME] = std::bit_cast<uint32_t>(frameTime);
  h[GB_CONTACT_SLACK] = std::bit_cast<uint32_t>(slack);
  return h;
}

void VulkanStepper::Impl::searchContacts(float frameTime, float slack, const ContactHistory& history) {
  ensureContactRoom(0, history.contacts.size());
  const gpu::ContactSearchLayout l = contactLayout();
  DeviceBuffer& contacts = buffer(GB_BINDING_CONTACTS);
  // The device's own list is the history also when the film grew on the device since (updateRegion): its particles
  // kept their numbers, and the list its count.
  const bool historyOnDevice =
      deviceListEntries > 0 &&
      (history.onDevice || (history.particles == particles && history.contacts.size() == deviceListEntries));
  uint32_t previousParticles = static_cast<uint32_t>(history.particles);
  if (!historyOnDevice) {
    const bool listed = !history.contacts.empty() && history.contacts.size() >= history.particles + 1;
    previousParticles = listed ? static_cast<uint32_t>(history.particles) : 0u;
    if (listed)
      contacts.write(history.contacts.data(), history.contacts.size() * sizeof(uint32_t),
                     size_t{l.previous} * sizeof(uint32_t));
  }
  const vk::raii::CommandBuffer& cb = commands;
  cb.reset();
  cb.begin({vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
  cb.updateBuffer<uint32_t>(contacts.handle(), vk::DeviceSize{l.header} * sizeof(uint32_t),
                            contactSearchHeader(frameTime, slack, previousParticles));
  cb.fillBuffer(contacts.handle(), vk::DeviceSize{l.bucketStart} * sizeof(uint32_t),
                (vk::DeviceSize{contactBuckets} + 1) * sizeof(uint32_t), 0u);
  if (historyOnDevice)
    cb.copyBuffer(
        contacts.handle(), contacts.handle(),
        vk::BufferCopy(0, vk::DeviceSize{l.previous} * sizeof(uint32_t), deviceListEntries * sizeof(uint32_t)));
  transferToComputeBarrier(cb);  // the header, the zeroed counts and the previous list are in place
  const uint32_t header = l.header;
  const uint32_t runs = gpu::contactReachGroups(particles, workgroup);
  dispatchGroups(cb, Kernel::ContactReach, runs, particles, 0, 0, header);  // each run's velocity sum
  computeToComputeBarrier(cb);
  dispatchGroups(cb, Kernel::ContactReach, runs, particles, 0, GB_REACH_FASTEST, header);  // about the mean
  computeToComputeBarrier(cb);
  dispatchGroups(cb, Kernel::ContactReach, 1, particles, 0, GB_REACH_FINAL, header);  // the largest: the reach
  computeToComputeBarrier(cb);                                                        // the reach sizes the cells
  dispatch(cb, Kernel::ContactCells, particles, 0, 0, header);
  computeToComputeBarrier(cb);  // every particle is counted before the counts are scanned
  recordContactScan(cb, contactBuckets + 1, 0);
  dispatch(cb, Kernel::ContactSort, particles, 0, 0, header);
  computeToComputeBarrier(cb);  // every bucket is filled before anyone reads it
  dispatch(cb, Kernel::ContactSheets, contactBuckets, 0, 0, header);
  computeToComputeBarrier(cb);  // every bucket's sheet is summarised before the pairs read them
  dispatch(cb, Kernel::ContactPairs, particles, 0, 0, header);
  computeToComputeBarrier(cb);  // every row is counted before the counts are scanned
  recordContactScan(cb, particles + 1, GB_SCAN_ROWS);
  dispatch(cb, Kernel::ContactWrite, particles, 0, 0, header);
  computeToHostBarrier(cb);
  cb.end();
  ctx->submitAndWait(cb);
  ++contactRecord.searches;
}

bool VulkanStepper::Impl::contactSearchHadRoom(const ContactHistory& history) {
  std::array<uint32_t, GB_CONTACT_HEADER> h{};
  readFrom(buffer(GB_BINDING_CONTACTS), h.data(), sizeof h, vk::DeviceSize{contactHeader()} * sizeof(uint32_t));
  const uint32_t most = h[GB_CONTACT_MOST_PARTNERS], entries = h[GB_CONTACT_PARTNER_ENTRIES];
  if (most <= contactRowCapacity && entries <= contactEntryCapacity) return true;
  std::fprintf(stderr,
               "vulkan: the contact search found %u partners of one particle and %u in all, with room for %u and "
               "%u: searching again with more room\n",
               most, entries, contactRowCapacity, contactEntryCapacity);
  if (history.onDevice && deviceListEntries > 0)  // from where the search's layout put it: the old room's
    copyContactUints(buffer(GB_BINDING_CONTACTS), contactLayout().previous, buffer(GB_BINDING_CONTACTS), 0,
                     deviceListEntries);
  else
    deviceListEntries = 0;
  if (most > contactRowCapacity) contactRowCapacity = std::max(most, 2 * contactRowCapacity);  // a film crumples on
  ensureContactRoom(entries, 0);
  ++contactRecord.regrown;
  return false;
}

void VulkanStepper::Impl::countContactList() {
  uint32_t entries = 0;
  readFrom(buffer(GB_BINDING_CONTACTS), &entries, sizeof entries, vk::DeviceSize{particles} * sizeof(uint32_t));
  deviceListEntries = particles + size_t{1} + 2 * size_t{entries};
}

void VulkanStepper::Impl::readContactList(std::vector<uint32_t>& contacts) {
  contacts.resize(deviceListEntries);
  readFrom(buffer(GB_BINDING_CONTACTS), contacts.data(), contacts.size() * sizeof(uint32_t));
}

void VulkanStepper::updateContacts(const Film& film) { impl_->writeContacts(film.topology); }

bool VulkanStepper::findContacts(const Params& params, float frameTime, float slack, Film& film,
                                 const ContactHistory& history) {
  if (film.state.size() != impl_->particles) throw std::logic_error("VulkanStepper::findContacts: not the loaded film");
  if (!findContactsOnDevice(params, frameTime, slack, history)) return false;
  storeContacts(film);
  return true;
}

bool VulkanStepper::findContactsOnDevice(const Params& params, float frameTime, float slack,
                                         const ContactHistory& history) {
  Impl& m = *impl_;
  if (!m.contactsOnDevice) return false;
  if (m.sets.empty()) throw std::logic_error("VulkanStepper: no film loaded");
  if (params.collisionDistance != m.params->collisionDistance ||
      params.collisionStiffness != m.params->collisionStiffness)
    throw std::logic_error("VulkanStepper::findContacts: not the loaded film");
  // A search short of room lists nothing reliable: it runs once more with the room it found it needed.
  m.searchContacts(frameTime, slack, history);
  if (!m.contactSearchHadRoom(history)) {
    m.searchContacts(frameTime, slack, history);
    if (!m.contactSearchHadRoom(history)) throw std::logic_error("VulkanStepper::findContacts: no room after growing");
  }
  m.countContactList();
  return true;
}

void VulkanStepper::storeContacts(Film& film) {
  Impl& m = *impl_;
  if (m.deviceListEntries == 0) return;  // the list the CPU gave (updateContacts, load) is the one there
  if (film.state.size() != m.particles) throw std::logic_error("VulkanStepper::storeContacts: not the loaded film");
  m.readContactList(film.topology.contacts);
}

const DeviceContactRecord& VulkanStepper::contactRecord() const { return impl_->contactRecord; }

}  // namespace gb
